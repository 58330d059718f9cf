// LineBits: the packed line-level sequence, which is also the on-disk `bits` capture format
// (brief: MSB first within each byte, bit i = (bytes[i/8] >> (7 - i%8)) & 1, 1 = high).
#include "sercon/wire/line_bits.hpp"

#include <gtest/gtest.h>

#include <random>
#include <stdexcept>
#include <vector>

namespace sercon::wire {
namespace {

// Format: bit i is (bytes[i/8] >> (7 - i%8)) & 1.
TEST(LineBits, FromPackedIsMsbFirst) {
  const LineBits b = LineBits::from_packed({0xA0, 0x01}, 16);
  ASSERT_EQ(b.size(), 16u);
  EXPECT_TRUE(b[0]);
  EXPECT_FALSE(b[1]);
  EXPECT_TRUE(b[2]);
  EXPECT_FALSE(b[3]);
  EXPECT_TRUE(b[15]);
  EXPECT_FALSE(b[14]);
}

// Format: bits past bit_count are not part of the line and read back as 0 in packed().
TEST(LineBits, FromPackedIgnoresTrailingBitsAndBytes) {
  const LineBits b = LineBits::from_packed({0xFF, 0xFF, 0xFF}, 12);
  ASSERT_EQ(b.size(), 12u);
  ASSERT_EQ(b.packed().size(), 2u);
  EXPECT_EQ(b.packed()[0], 0xFF);
  EXPECT_EQ(b.packed()[1], 0xF0);
  EXPECT_EQ(b.word_at(0), 0xFFF0000000000000ull);
}

// Brief (from_packed throws std::invalid_argument): more bits than the bytes hold.
TEST(LineBits, FromPackedRejectsTooManyBits) {
  EXPECT_THROW(LineBits::from_packed({0x00}, 9), std::invalid_argument);
  EXPECT_THROW(LineBits::from_packed({}, 1), std::invalid_argument);
  EXPECT_NO_THROW(LineBits::from_packed({0x00}, 8));
  EXPECT_NO_THROW(LineBits::from_packed({}, 0));
  const LineBits b = LineBits::from_packed({0x00}, 8);
  EXPECT_THROW((void)b.at(8), std::out_of_range);
}

// Format (brief: `bits` capture format): appends at any alignment agree with push_back,
// and packed() holds bit i at (bytes[i/8] >> (7 - i%8)) & 1.
TEST(LineBits, AppendAtAnyAlignmentMatchesPushBack) {
  std::mt19937_64 rng(1);
  for (int round = 0; round < 200; ++round) {
    LineBits a;
    LineBits b;
    std::vector<bool> ref;
    for (int piece = 0; piece < 20; ++piece) {
      const unsigned n = static_cast<unsigned>(rng() % 65);
      const std::uint64_t v = rng();
      a.append(v, n);
      for (unsigned i = 0; i < n; ++i) {
        const bool bit = ((v >> (63 - i)) & 1u) != 0;
        b.push_back(bit);
        ref.push_back(bit);
      }
      const bool run_level = (rng() & 1u) != 0;
      const std::size_t run = rng() % 140;
      a.append_run(run_level, run);
      for (std::size_t i = 0; i < run; ++i) {
        b.push_back(run_level);
        ref.push_back(run_level);
      }
    }
    ASSERT_EQ(a, b);
    ASSERT_EQ(a.size(), ref.size());
    const auto packed = a.packed();
    for (std::size_t i = 0; i < ref.size(); ++i) {
      ASSERT_EQ(a[i], ref[i]) << i;
      ASSERT_EQ(((unsigned{packed[i / 8]} >> (7 - i % 8)) & 1u) != 0, ref[i]) << i;
    }
    for (std::size_t i = 0; i < ref.size(); i += 13) {
      const std::uint64_t w = a.word_at(i);
      for (std::size_t k = 0; k < 64; ++k) {
        const bool expect = i + k < ref.size() && ref[i + k];
        ASSERT_EQ(((w >> (63 - k)) & 1u) != 0, expect) << i << "+" << k;
      }
    }
    LineBits c;
    c.append(a);
    c.append(b);
    ASSERT_EQ(c.size(), 2 * a.size());
    for (std::size_t i = 0; i < a.size(); ++i) ASSERT_EQ(c[a.size() + i], a[i]);
  }
}

// Format (brief: `bits` capture format): from_packed(packed()) reproduces the line, the
// round trip a capture file takes.
TEST(LineBits, PackedRoundTrip) {
  LineBits a;
  for (int i = 0; i < 77; ++i) a.push_back(i % 3 == 0);
  const LineBits b = LineBits::from_packed(a.packed_copy(), a.size());
  EXPECT_EQ(a, b);
  a.clear();
  EXPECT_TRUE(a.empty());
  a.push_back(false);
  EXPECT_EQ(a.packed()[0], 0x00);
}

// A new line holds no buffer until its first bit; every read of it must still work.
TEST(LineBits, EmptyLineReadsAndGrows) {
  LineBits a;
  EXPECT_TRUE(a.packed().empty());
  EXPECT_TRUE(a.packed_copy().empty());
  EXPECT_EQ(a.word_at(0), 0u);
  EXPECT_THROW((void)a.at(0), std::out_of_range);
  EXPECT_EQ(a, LineBits());
  EXPECT_EQ(a, LineBits::from_packed({}, 0));
  a.clear();
  a.append(LineBits());
  a.append(0, 0);
  EXPECT_TRUE(a.empty());
  LineBits dark;
  dark.append_run(false, 3);
  EXPECT_EQ(dark.packed_copy(), std::vector<std::uint8_t>{0x00});
  LineBits b;
  b.append(LineBits::from_packed({0xA5}, 8));
  EXPECT_EQ(b.packed_copy(), std::vector<std::uint8_t>{0xA5});
  EXPECT_EQ(b.word_at(0), 0xA5ull << 56);
}

}  // namespace
}  // namespace sercon::wire

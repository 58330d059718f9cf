// Bits objects are recycled (docs/serial-and-ring.md, "Bits objects are recycled";
// shared_bits.hpp): a released object is taken again by the next one made on the thread,
// with its bit buffer and its whole decode's storage, and carries nothing else of its past.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <vector>

#include "sercon/chip/line_decode_memo.hpp"
#include "sercon/chip/shared_bits.hpp"
#include "sercon/wire/encoder.hpp"

namespace sercon::chip {
namespace {

// A telegram as the transmitter makes it: encoded in place, its decode seeded.
SharedBits sent(std::uint8_t address, const std::vector<std::uint8_t>& data) {
  wire::EncodedFrame where;
  std::uint16_t fcs = 0;
  SharedBits bits = write_shared_bits([&](wire::LineBits& out) {
    EXPECT_TRUE(out.empty());
    wire::LineEncoder encoder(true, std::move(out));
    where = encoder.telegram(address, data);
    fcs = encoder.fcs();
    out = encoder.take();
  });
  EXPECT_EQ(bits.decodes().whole, nullptr);
  EXPECT_TRUE(bits.decodes().prefixes.empty());
  seed_decode(bits, where, address, data, fcs);
  return bits;
}

// The seed matches what a decoder finds in a copy of the bits, field by field.
void expect_seed_decodes(const SharedBits& bits) {
  const BurstDecode& seed = decode_burst(bits);
  const SharedBits copy = share_bits(*bits);
  const BurstDecode& decoded = decode_burst(copy);
  ASSERT_EQ(seed.frames.size(), decoded.frames.size());
  EXPECT_EQ(seed.address_end, decoded.address_end);
  for (std::size_t i = 0; i < seed.frames.size(); ++i) {
    EXPECT_EQ(seed.frames[i].start_bit, decoded.frames[i].start_bit);
    EXPECT_EQ(seed.frames[i].end_bit, decoded.frames[i].end_bit);
    EXPECT_EQ(seed.frames[i].address, decoded.frames[i].address);
    EXPECT_EQ(seed.frames[i].data, decoded.frames[i].data);
    EXPECT_EQ(seed.frames[i].fcs_received, decoded.frames[i].fcs_received);
    EXPECT_EQ(seed.frames[i].fcs_computed, decoded.frames[i].fcs_computed);
    EXPECT_EQ(seed.frames[i].error, decoded.frames[i].error);
  }
}

TEST(serial_SharedBits, AReleasedObjectIsTakenAgainWithItsStorage) {
  if (!kRecycleBits) GTEST_SKIP() << "nothing is recycled under AddressSanitizer (shared_bits.hpp)";
  // Held, these take every object the thread's free list holds (an earlier test may have
  // filled it), so the one released below is not refused for a full list.
  std::vector<SharedBits> held;
  for (int i = 0; i < 1100; ++i) held.push_back(share_bits(wire::LineBits()));
  const wire::LineBits* node = nullptr;
  const BurstDecode* decode = nullptr;
  {
    const SharedBits first = sent(0x12, std::vector<std::uint8_t>(40, 0xA5));
    node = first.get();
    decode = first.decodes().whole.get();
  }
  const SharedBits second = sent(0x34, {0x01, 0x02});
  EXPECT_EQ(second.get(), node);
  EXPECT_EQ(second.decodes().whole.get(), decode);  // the kept decode, filled again
  expect_seed_decodes(second);
}

// A ring of 254 slaves has some 256 telegrams a cycle, let go of together when its cycle is
// over: the free list keeps them all (up to 1024), so the next cycle's telegrams are all
// recycled objects, not new allocations (docs/serial-and-ring.md, "Bits objects are
// recycled"). With 128 kept, half of them were freed and allocated again every cycle.
TEST(serial_SharedBits, ARingsCycleOfTelegramsIsAllTakenAgain) {
  if (!kRecycleBits) GTEST_SKIP() << "nothing is recycled under AddressSanitizer (shared_bits.hpp)";
  std::vector<SharedBits> held;  // empty the free list first (as in the test above)
  for (int i = 0; i < 1100; ++i) held.push_back(share_bits(wire::LineBits()));
  std::vector<const wire::LineBits*> before;
  {
    std::vector<SharedBits> cycle;
    for (int i = 0; i < 300; ++i) cycle.push_back(sent(static_cast<std::uint8_t>(i), {0x01, 0x02}));
    for (const SharedBits& b : cycle) before.push_back(b.get());
  }
  std::vector<SharedBits> next;
  for (int i = 0; i < 300; ++i) next.push_back(sent(static_cast<std::uint8_t>(i), {0x03, 0x04}));
  for (const SharedBits& b : next) {
    EXPECT_NE(std::find(before.begin(), before.end(), b.get()), before.end());
  }
}

TEST(serial_SharedBits, ARecycledDecodeKeepsNothingOfItsPast) {
  // ok, then too short (no data: the FCS fields are 0), then ok again, on one object.
  { expect_seed_decodes(sent(0xFF, std::vector<std::uint8_t>(300, 0xFF))); }
  { expect_seed_decodes(sent(0x00, {})); }
  { expect_seed_decodes(sent(0x7E, {0x7E})); }
  // A decoder's decode (several frames possible) kept, then a seed in its place.
  {
    wire::LineEncoder two(true);
    two.telegram(0x01, std::vector<std::uint8_t>{0x10, 0x20});
    two.telegram(0x02, std::vector<std::uint8_t>{0x30});
    const SharedBits both = share_bits(two.take());
    EXPECT_EQ(decode_burst(both).frames.size(), 2u);
    decode_burst_prefix(both, 20);
  }
  const SharedBits after = sent(0x05, {0x99, 0x98, 0x97});
  EXPECT_TRUE(after.decodes().prefixes.empty());
  ASSERT_EQ(decode_burst(after).frames.size(), 1u);
  expect_seed_decodes(after);
}

}  // namespace
}  // namespace sercon::chip

// The transmitter's seeded decode (line_decode_memo.hpp, seed_decode) is exactly the decode a
// receiver would make of the same bits. A telegram is flag, address, data, FCS (low byte
// first), flag, bytes LSB first, a 0 stuffed after five 1s, NRZI (sercos-facts.md §1;
// docs/wire.md, "Encoder" and "Decoder: decisions"); a receiver decodes each burst with a
// lead-in bit before it, positions counted from the burst's first bit, and reports every
// frame with where its address byte ends (docs/serial-and-ring.md, "Receiver"). The seed
// must give the same frames field by field, for any address and data, runs of 0xFF
// (stuffing) included.
#include <gtest/gtest.h>

#include <cstdint>
#include <random>
#include <vector>

#include "sercon/chip/line_decode_memo.hpp"
#include "sercon/chip/line_decode_seed.hpp"
#include "sercon/wire/encoder.hpp"
#include "serial_bench.hpp"

namespace sercon::chip {
namespace {

using testing::SerialBench;

void expect_same(const BurstDecode& seeded, const BurstDecode& decoded) {
  ASSERT_EQ(seeded.frames.size(), decoded.frames.size());
  ASSERT_EQ(seeded.address_end, decoded.address_end);
  EXPECT_EQ(seeded.to_255, decoded.to_255);  // a lazy hop asks it: stale, an MST could pass
  for (std::size_t i = 0; i < seeded.frames.size(); ++i) {
    const wire::DecodedFrame& s = seeded.frames[i];
    const wire::DecodedFrame& d = decoded.frames[i];
    EXPECT_EQ(s.start_bit, d.start_bit) << i;
    EXPECT_EQ(s.end_bit, d.end_bit) << i;
    EXPECT_EQ(s.address, d.address) << i;
    EXPECT_EQ(s.data, d.data) << i;
    EXPECT_EQ(s.fcs_received, d.fcs_received) << i;
    EXPECT_EQ(s.fcs_computed, d.fcs_computed) << i;
    EXPECT_EQ(s.error, d.error) << i;
    EXPECT_EQ(s.ok(), d.ok()) << i;
  }
}

// Encodes the telegram twice from the same level: one copy seeded as the transmitter does,
// the other decoded as a receiver does (no seed); both decodes must match.
void check(std::uint8_t address, const std::vector<std::uint8_t>& data, bool level_before) {
  wire::LineEncoder seeding(level_before);
  const wire::EncodedFrame where = seeding.telegram(address, data);
  const SharedBits seeded = share_bits(seeding.take());
  wire::LineEncoder plain(level_before);
  plain.telegram(address, data);
  const SharedBits decoded = share_bits(plain.take());
  ASSERT_EQ(*seeded, *decoded);

  const std::size_t before = burst_decode_count();
  seed_decode(seeded, where, address, data, seeding.fcs());
  ASSERT_NE(seeded.decodes().whole.get(), nullptr);
  const BurstDecode* seed = seeded.decodes().whole.get();
  EXPECT_EQ(&decode_burst(seeded), seed);       // a receiver takes the seed, decodes nothing
  EXPECT_EQ(burst_decode_count(), before + 1);  // the seed counts as the burst's one decode
  const BurstDecode& reference = decode_burst(decoded);
  EXPECT_EQ(burst_decode_count(), before + 2);
  expect_same(*seed, reference);
}

TEST(serial_DecodeSeed, EdgeCases) {
  check(0x00, {}, true);  // no data: TooShort, the FCS bytes as data
  check(0xFF, {}, false);
  check(0xFF, {0x00}, true);                    // shortest ok telegram
  check(0x1F, {0xFF, 0xFF, 0xFF, 0xFF}, true);  // stuffing in and after the address
  check(0xF8, {0x7E, 0x7E, 0xFF}, false);       // flag-like data
  check(0x3F, std::vector<std::uint8_t>(80, 0xFF), true);
  check(0x01, std::vector<std::uint8_t>(80, 0x00), false);
  check(0x7F, std::vector<std::uint8_t>(300, 0xFF), false);  // past the decoder's inline buffer
}

TEST(serial_DecodeSeed, RandomTelegramsSeedWhatTheDecoderFinds) {
  std::mt19937_64 rng(0x5EED);
  std::uniform_int_distribution<unsigned> byte(0, 255);
  std::uniform_int_distribution<std::size_t> words(0, 40);
  std::bernoulli_distribution ff_run(0.2);
  std::uniform_int_distribution<std::size_t> run_length(1, 8);
  for (int n = 0; n < 3000; ++n) {
    const auto address = static_cast<std::uint8_t>(byte(rng));
    const std::size_t size = 2 * words(rng) + (n % 7 == 0 ? 1 : 0);  // odd sizes too
    std::vector<std::uint8_t> data;
    while (data.size() < size) {
      if (ff_run(rng)) {
        for (std::size_t k = run_length(rng); k > 0 && data.size() < size; --k)
          data.push_back(0xFF);
      } else {
        data.push_back(static_cast<std::uint8_t>(byte(rng)));
      }
    }
    check(address, data, (n & 1) != 0);
    if (::testing::Test::HasFailure()) {
      ADD_FAILURE() << "telegram " << n << " address " << unsigned{address} << " size " << size;
      return;
    }
  }
}

// encode_seeded writes a recycled object over as its last holder left it
// (line_decode_memo.hpp). Its bits, the bytes past them, the level after them and every
// field of its decode must be what the general path gives, a fresh object cleared,
// encoded (wire::encode_telegram) and seeded (seed_decode), whatever the object held
// before: a longer or shorter telegram, a decoder's decode of several frames, cut decodes.
TEST(serial_DecodeSeed, EncodeSeededIsTheGeneralPath) {
  std::mt19937_64 rng(0x7E1E);
  std::vector<SharedBits> held;  // some telegrams still held when the next is coded
  std::uniform_int_distribution<unsigned> byte(0, 255);
  std::uniform_int_distribution<std::size_t> size(0, 120);
  std::bernoulli_distribution ff(0.3);
  for (int n = 0; n < 2000; ++n) {
    if (n % 5 == 0) {  // leave a decoder's decodes on the next object taken
      wire::LineEncoder two(n % 2 == 0);
      two.telegram(0x01, std::vector<std::uint8_t>(size(rng), 0xFF));
      two.telegram(0x02, std::vector<std::uint8_t>{0x30});
      const SharedBits both = share_bits(two.take());
      decode_burst(both);
      decode_burst_prefix(both, 20);
    }
    const auto address = static_cast<std::uint8_t>(byte(rng));
    std::vector<std::uint8_t> data(size(rng) / (n % 3 == 0 ? 1 : 12));
    for (std::uint8_t& b : data) b = ff(rng) ? 0xFF : static_cast<std::uint8_t>(byte(rng));
    const bool level_before = (n & 2) != 0;

    bool level = level_before;
    const std::size_t before = burst_decode_count();
    const SharedBits rewritten = encode_seeded(level, address, data);
    EXPECT_EQ(burst_decode_count(), before + 1);
    if (n % 4 == 1) held.push_back(rewritten);
    if (held.size() > 3) held.erase(held.begin());

    wire::TelegramCoding c;
    const SharedBits general = write_shared_bits(
        [&](wire::LineBits& out) { c = wire::encode_telegram(out, level_before, address, data); });
    seed_decode(general, c.frame, address, data, c.fcs);

    ASSERT_EQ(*rewritten, *general) << "telegram " << n;
    EXPECT_EQ(level, c.level_after) << n;
    // The bytes past the bits are 0 (LineBits), up to the longest telegram of the test.
    wire::LineBits grown = *rewritten;
    grown.append_run(false, 2000);
    wire::LineBits expected = *general;
    expected.append_run(false, 2000);
    ASSERT_EQ(grown, expected) << "telegram " << n;
    EXPECT_TRUE(rewritten.decodes().prefixes.empty());
    ASSERT_NE(rewritten.decodes().whole.get(), nullptr);
    EXPECT_EQ(&decode_burst(rewritten), rewritten.decodes().whole.get());
    expect_same(*rewritten.decodes().whole, *general.decodes().whole);
    expect_same(*rewritten.decodes().whole, decode_burst(share_bits(*general)));
    if (::testing::Test::HasFailure()) {
      ADD_FAILURE() << "telegram " << n << " address " << unsigned{address} << " size "
                    << data.size();
      return;
    }
  }
}

// The transmitter seeds every telegram it sends: the burst on TxD carries its decode, the
// same as a receiver makes from a copy of the bits, and no receiver decodes it again.
TEST(serial_DecodeSeed, TransmitterSeedsItsTelegrams) {
  SerialBench b;
  b.light_up();
  const sim::Time t = b.period();
  const std::vector<std::uint8_t> data{0xFF, 0xFF, 0x7E, 0x00, 0x12, 0xFF};
  const std::size_t before = SerialUnit::decode_count();
  const sim::Time end = b.unit.send(100 * t, 0xFE, data);
  EXPECT_EQ(SerialUnit::decode_count(), before + 1);
  b.run_to(end + 100 * t);
  const auto bursts = b.txd1.bursts();
  ASSERT_EQ(bursts.size(), 1u);
  const SharedBits& bits = bursts[0].bits;
  ASSERT_NE(bits.decodes().whole.get(), nullptr);
  const BurstDecode* seed = bits.decodes().whole.get();
  EXPECT_EQ(&decode_burst(bits), seed);
  const SharedBits copy = share_bits(*bits);
  expect_same(*seed, decode_burst(copy));
  ASSERT_EQ(seed->frames.size(), 1u);
  EXPECT_TRUE(seed->frames[0].ok());
  EXPECT_EQ(seed->frames[0].data, data);
}

}  // namespace
}  // namespace sercon::chip

// The table-driven decoder against the independent reference decoder (reference_decoder
// .hpp, written straight from sercos-facts §1 as patterns) on noise and on encoded
// streams with every error class, fed whole and in random chunks.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

#include "reference_decoder.hpp"
#include "sercon/wire/decoder.hpp"
#include "sercon/wire/encoder.hpp"
#include "wire_test_util.hpp"

namespace sercon::wire {
namespace {

void expect_equal(const std::vector<DecodedFrame>& want, const std::vector<DecodedFrame>& got,
                  std::uint64_t seed) {
  ASSERT_EQ(want.size(), got.size()) << "seed " << seed;
  for (std::size_t i = 0; i < want.size(); ++i) {
    ASSERT_EQ(want[i].start_bit, got[i].start_bit) << "seed " << seed << " frame " << i;
    ASSERT_EQ(want[i].end_bit, got[i].end_bit) << "seed " << seed << " frame " << i;
    ASSERT_EQ(want[i].error, got[i].error) << "seed " << seed << " frame " << i;
    ASSERT_EQ(want[i].address, got[i].address) << "seed " << seed << " frame " << i;
    ASSERT_EQ(want[i].data, got[i].data) << "seed " << seed << " frame " << i;
    ASSERT_EQ(want[i].fcs_received, got[i].fcs_received) << "seed " << seed;
    ASSERT_EQ(want[i].fcs_computed, got[i].fcs_computed) << "seed " << seed;
  }
}

std::vector<DecodedFrame> decode_chunked(const LineBits& line, std::mt19937_64& rng) {
  std::vector<DecodedFrame> out;
  LineDecoder dec([&](const DecodedFrame& f) { out.push_back(f); });
  std::size_t i = 0;
  while (i < line.size()) {
    const std::size_t n = std::min<std::size_t>(line.size() - i, rng() % 100);
    LineBits chunk;
    for (std::size_t k = 0; k < n; ++k) chunk.push_back(line[i + k]);
    dec.feed(chunk);
    i += n;
  }
  dec.finish();
  return out;
}

// sercos-facts §1 as a pattern reading, versus the tables: line noise with runs of 1..8
// equal levels, so flags, stuffing, aborts and frames of every kind occur.
TEST(DecoderReference, AgreesOnNoise) {
  for (std::uint64_t seed = 1; seed <= 300; ++seed) {
    std::mt19937_64 rng(seed);
    LineBits line;
    bool level = (seed & 1) != 0;
    const std::size_t n = 200 + rng() % 3000;
    while (line.size() < n) {
      line.append_run(level, 1 + rng() % (seed % 3 == 0 ? 8 : 7));
      level = !level;
    }
    const auto want = test::reference_decode(line);
    expect_equal(want, decode_all(line), seed);
    expect_equal(want, decode_chunked(line, rng), seed);
  }
}

// sercos-facts §1: encoded telegrams mixed with injected errors, versus the reference.
TEST(DecoderReference, AgreesOnEncodedStreamsWithErrors) {
  using Bytes = std::vector<std::uint8_t>;
  for (std::uint64_t seed = 1; seed <= 100; ++seed) {
    std::mt19937_64 rng(seed);
    LineEncoder enc((seed & 2) != 0);
    enc.idle(rng() % 20);
    for (int i = 0; i < 30; ++i) {
      switch (rng() % 7) {
        case 0:
          enc.raw_frame(Bytes{0xFF, 0x00, 0x00, 0x00});
          break;
        case 1:
          enc.flag();
          enc.stuffed_bytes(Bytes(rng() % 5, 0xFF));
          enc.raw_decoded_bits("1111111");
          break;
        case 2:
          enc.raw_frame(Bytes(rng() % 4, 0x7E));
          break;
        case 3:
          enc.flag();
          enc.stuffed_bytes(test::random_telegram(rng, 0, 6).data);
          enc.raw_decoded_bits(rng(), static_cast<unsigned>(rng() % 8));
          enc.flag();
          break;
        case 4:
          enc.raw_decoded_bits(rng(), static_cast<unsigned>(rng() % 64));
          break;
        default:
          enc.telegram(test::random_telegram(rng, 1, 40));
          break;
      }
      enc.idle(rng() % 24);
    }
    const auto want = test::reference_decode(enc.bits());
    expect_equal(want, decode_all(enc.bits()), seed);
    expect_equal(want, decode_chunked(enc.bits(), rng), seed);
  }
}

}  // namespace
}  // namespace sercon::wire

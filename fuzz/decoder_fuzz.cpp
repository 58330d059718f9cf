// libFuzzer target for the line decoder: random bytes are a line (packed levels, MSB
// first). Checks that the table-driven decoder agrees with the independent reference
// decoder of the tests (tests/wire/reference_decoder.hpp), that chunked feeding (LineBits chunks
// and packed-byte chunks) reports exactly what whole feeding does, that frames are ordered and
// inside the input, and that a frame without error carries a matching FCS. The same bytes as a
// telegram must also survive an encode/decode round trip.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <span>
#include <vector>

#include "sercon/wire/decoder.hpp"
#include "sercon/wire/encoder.hpp"
#include "sercon/wire/fcs.hpp"
#include "sercon/wire/line_bits.hpp"
#include "wire/reference_decoder.hpp"

namespace {

using sercon::wire::DecodedFrame;
using sercon::wire::FrameError;
using sercon::wire::LineBits;
using sercon::wire::LineDecoder;

void check(bool ok, const char* what) {
  if (!ok) {
    std::fprintf(stderr, "decoder_fuzz: invariant violated: %s\n", what);
    std::abort();
  }
}

bool same(const DecodedFrame& a, const DecodedFrame& b) {
  return a.start_bit == b.start_bit && a.end_bit == b.end_bit && a.address == b.address &&
         a.data == b.data && a.fcs_received == b.fcs_received && a.fcs_computed == b.fcs_computed &&
         a.error == b.error;
}

void check_invariants(const std::vector<DecodedFrame>& frames, std::size_t bit_count) {
  std::size_t last_start = 0;
  std::size_t last_end = 0;
  for (const DecodedFrame& f : frames) {
    check(f.start_bit >= last_start, "frames ordered by start");
    check(f.end_bit >= last_end, "frames ordered by end");
    check(f.start_bit + 16 <= f.end_bit || f.error == FrameError::Abort ||
              f.error == FrameError::Truncated,
          "a closed frame spans two flags");
    check(f.end_bit <= bit_count, "frame inside the input");
    if (f.error == FrameError::None || f.error == FrameError::BadFcs) {
      std::vector<std::uint8_t> body = {f.address};
      body.insert(body.end(), f.data.begin(), f.data.end());
      check(!f.data.empty(), "a checked frame has data");
      check(sercon::wire::fcs16(body) == f.fcs_computed, "fcs_computed is the FCS");
      check((f.error == FrameError::None) == (f.fcs_received == f.fcs_computed),
            "None exactly when the FCS matches");
    } else {
      check(f.fcs_received == 0 && f.fcs_computed == 0, "no FCS on unchecked frames");
    }
    last_start = f.start_bit;
    last_end = f.end_bit;
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::span<const std::uint8_t> bytes(data, size);
  const std::size_t bit_count = size * 8;
  const LineBits line = LineBits::from_packed({bytes.begin(), bytes.end()}, bit_count);
  const std::vector<DecodedFrame> whole = sercon::wire::decode_all(line);
  check_invariants(whole, bit_count);
  const std::vector<DecodedFrame> reference = sercon::wire::test::reference_decode(line);
  check(reference.size() == whole.size(), "reference decoder finds the same number of frames");
  for (std::size_t i = 0; i < whole.size(); ++i)
    check(same(whole[i], reference[i]), "reference decoder reports the same frame");

  // Chunk sizes from a tiny generator seeded by the input, so runs are reproducible.
  std::uint32_t seed = 2166136261u;
  for (std::uint8_t b : bytes.first(size < 8 ? size : 8)) seed = (seed ^ b) * 16777619u;
  std::vector<DecodedFrame> chunked;
  LineDecoder decoder([&](const DecodedFrame& f) { chunked.push_back(f); });
  std::size_t pos = 0;
  bool packed = false;
  while (pos < bit_count) {
    seed = seed * 1103515245u + 12345u;
    std::size_t n = (seed >> 16) % 150;
    if (n > bit_count - pos) n = bit_count - pos;
    LineBits chunk;
    for (std::size_t i = 0; i < n; ++i) chunk.push_back(line[pos + i]);
    if (packed)
      decoder.feed(chunk.packed(), chunk.size());
    else
      decoder.feed(chunk);
    packed = !packed;
    pos += n;
  }
  decoder.finish();
  check(chunked.size() == whole.size(), "chunked feeding finds the same number of frames");
  for (std::size_t i = 0; i < whole.size(); ++i)
    check(same(whole[i], chunked[i]), "chunked feeding reports the same frame");

  // The input as a telegram: address + data round-trips through the line code.
  if (size >= 2) {
    sercon::wire::LineEncoder enc((data[0] & 1u) != 0);
    enc.idle(8 + data[1] % 16);
    const auto where = enc.telegram(data[0], bytes.subspan(1));
    enc.idle(data[1] % 9);
    const auto frames = sercon::wire::decode_all(enc.bits());
    check(frames.size() == 1, "one telegram in, one frame out");
    check(frames[0].error == FrameError::None, "encoded telegram decodes without error");
    check(frames[0].address == data[0], "address round trip");
    check(std::equal(frames[0].data.begin(), frames[0].data.end(), data + 1, data + size) &&
              frames[0].data.size() == size - 1,
          "data round trip");
    check(frames[0].start_bit == where.start_bit && frames[0].end_bit == where.end_bit,
          "positions round trip");
  }
  return 0;
}

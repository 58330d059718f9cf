// A slow, obviously-correct decoder written independently of the table-driven one, used
// as its oracle by the tests and the fuzzer. It works on the whole decoded bit string:
// a flag is the pattern 01111110 (sercos-facts §1), a frame is the raw bits between two
// flags (or a flag and seven 1s, or the end) with every 0 after five 1s removed.
#pragma once

#include <cstdint>
#include <vector>

#include "sercon/wire/decoder.hpp"
#include "sercon/wire/fcs.hpp"
#include "sercon/wire/line_bits.hpp"

namespace sercon::wire::test {

inline std::vector<DecodedFrame> reference_decode(const LineBits& line) {
  const std::size_t n = line.size();
  // NRZI with line bit 0 as its own reference (docs/wire.md).
  std::vector<int> d(n);
  for (std::size_t i = 0; i < n; ++i) d[i] = (i == 0 || line[i] == line[i - 1]) ? 1 : 0;
  auto flag_ends_at = [&](std::size_t q) {  // d[q-7..q] == 0 1 1 1 1 1 1 0
    if (q < 7 || d[q] != 0 || d[q - 7] != 0) return false;
    for (std::size_t k = q - 6; k < q; ++k)
      if (d[k] != 1) return false;
    return true;
  };
  auto destuff = [&](std::size_t from, std::size_t to) {
    std::vector<int> out;
    int ones = 0;
    for (std::size_t i = from; i < to; ++i) {
      if (d[i] == 0 && ones == 5) {
        ones = 0;
        continue;
      }
      ones = d[i] ? ones + 1 : 0;
      out.push_back(d[i]);
    }
    return out;
  };

  std::vector<DecodedFrame> frames;
  auto report = [&](std::size_t start, std::size_t end, const std::vector<int>& bits,
                    FrameError forced) {
    if (bits.size() < 8) return;
    std::vector<std::uint8_t> bytes(bits.size() / 8, 0);
    for (std::size_t i = 0; i < bytes.size() * 8; ++i)
      bytes[i / 8] = static_cast<std::uint8_t>(bytes[i / 8] | bits[i] << (i % 8));
    DecodedFrame f;
    f.start_bit = start;
    f.end_bit = end;
    f.address = bytes[0];
    f.error = forced;
    if (forced == FrameError::None && bits.size() % 8 != 0) f.error = FrameError::Misaligned;
    if (f.error == FrameError::None && bytes.size() < 4) f.error = FrameError::TooShort;
    if (f.error == FrameError::None) {
      f.data.assign(bytes.begin() + 1, bytes.end() - 2);
      f.fcs_received =
          static_cast<std::uint16_t>(bytes[bytes.size() - 2] | bytes[bytes.size() - 1] << 8);
      f.fcs_computed = fcs16(std::vector<std::uint8_t>(bytes.begin(), bytes.end() - 2));
      if (f.fcs_received != f.fcs_computed) f.error = FrameError::BadFcs;
    } else {
      f.data.assign(bytes.begin() + 1, bytes.end());
    }
    frames.push_back(f);
  };

  std::size_t q = 7;
  while (q < n && !flag_ends_at(q)) ++q;  // first flag
  while (q < n) {
    // A frame opens after the flag ending at q; find what ends it.
    const std::size_t open = q;
    std::size_t i = open + 1;
    int ones = 0;
    bool ended = false;
    for (; i < n; ++i) {
      ones = d[i] ? ones + 1 : 0;
      if (flag_ends_at(i)) {  // the raw bits before the closing flag are the frame
        report(open - 7, i + 1, destuff(open + 1, i - 7), FrameError::None);
        q = i;  // this flag opens the next frame
        ended = true;
        break;
      }
      if (ones == 7) {  // abort: the run of 1s is not data
        report(open - 7, i + 1, destuff(open + 1, i - 6), FrameError::Abort);
        ended = true;
        break;
      }
    }
    if (!ended) {  // end of input: a trailing sixth 1 is not data (flag or abort pending)
      report(open - 7, n, destuff(open + 1, ones == 6 ? n - 1 : n), FrameError::Truncated);
      break;
    }
    if (q != i) {  // after an abort: hunt for the next flag
      q = i + 1;
      while (q < n && !flag_ends_at(q)) ++q;
    }
  }
  return frames;
}

}  // namespace sercon::wire::test

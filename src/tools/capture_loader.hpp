// Turns a capture file into recovered line bits with a time for every bit, whatever its
// format: the one place where format, --rate, --signal and clock recovery meet.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

#include "decode_options.hpp"
#include "sercon/capture/capture_format.hpp"
#include "sercon/wire/clock_recovery.hpp"

namespace sercon::tools {

struct LoadedCapture {
  capture::CaptureFormat format = capture::CaptureFormat::Bits;
  wire::RecoveredLine line;        // for `bits`: one anchor, bit 0 at time 0
  std::int64_t start_ps = 0;       // capture start on the line's time axis
  bool rate_given = false;         // --rate was given; otherwise it was detected
  std::string signal;              // the VCD signal or sigrok channel read; empty for bits
  std::size_t unknown_values = 0;  // VCD x/z values kept as "no change"

  // Time of line bit `bit` from the capture start, in ps.
  std::int64_t time_from_start_ps(std::size_t bit) const {
    return line.time_of_bit(bit) - start_ps;
  }
};

// Throws capture::CaptureError, wire::RecoveryError or InputError with a message that
// names the problem.
LoadedCapture load_capture(const DecodeOptions& options);

}  // namespace sercon::tools

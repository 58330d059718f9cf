// Facts about one decode run that the header and summary print.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

#include "sercon/capture/capture_format.hpp"

namespace sercon::tools {

struct DecodeRunInfo {
  std::string file;
  capture::CaptureFormat format = capture::CaptureFormat::Bits;
  std::int64_t bit_period_ps = 0;
  bool rate_given = false;         // --rate; otherwise detected from the capture
  std::string signal;              // VCD signal / sigrok channel; empty for bits
  std::size_t line_bits = 0;       // recovered line bits
  std::size_t unknown_values = 0;  // VCD x/z values kept as "no change"
};

}  // namespace sercon::tools

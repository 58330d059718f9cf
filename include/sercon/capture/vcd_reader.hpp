// Reads one 1-bit signal of a VCD file as line edges in picoseconds.
//
// x and z values are "level unknown": they keep the last known level (no edge) and are
// counted, so a capture with a glitch still decodes and the telegram around it is
// reported as broken rather than the whole file being refused.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <istream>
#include <string_view>
#include <vector>

#include "sercon/capture/vcd_variable.hpp"
#include "sercon/wire/clock_recovery.hpp"

namespace sercon::capture {

struct VcdTrace {
  VcdVariable variable;           // the signal that was read
  std::int64_t timescale_ps = 0;  // one VCD time unit
  std::int64_t start_ps = 0;      // first time stamp: the capture start
  std::int64_t end_ps = 0;        // last time stamp
  // The signal's first known level, taken to hold from start_ps; then every change, in
  // time order (the arguments of wire::recover_from_edges).
  bool initial_level = false;
  std::vector<wire::Edge> edges;
  std::size_t unknown_values = 0;  // x/z values seen on the signal
};

// `signal`: see select_vcd_variable(). `source` names the input in error messages.
// Throws CaptureError for malformed VCD, unknown identifier codes, times that go
// backwards, a signal that never has a known level, or one that never changes.
VcdTrace read_vcd(std::istream& in, std::string_view signal, std::string_view source);
VcdTrace read_vcd_file(const std::filesystem::path& file, std::string_view signal);

}  // namespace sercon::capture

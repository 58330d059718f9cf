// The VCD $timescale: how many picoseconds one VCD time unit lasts.
#pragma once

#include <cstdint>
#include <string_view>

namespace sercon::capture {

// Parses the text between $timescale and $end ("1ns", "1 ns", "100 us", ...): 1, 10 or 100
// of s, ms, us, ns, ps or fs. Returns the unit in picoseconds. Throws CaptureError for any
// other text, and for the fs units, which sercon's picosecond times cannot represent.
std::int64_t parse_vcd_timescale_ps(std::string_view text);

}  // namespace sercon::capture

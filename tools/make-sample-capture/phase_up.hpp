// The sample capture: a 4 Mbit/s four-drive ring phasing up from CP0 to CP4 as a real
// master does it (sercos-facts §2-§4), timings scaled down to keep the file small.
// captures/README.md describes the schedule; decode tests rely on its counts.
#pragma once

#include "sercon/wire/line_bits.hpp"

namespace sercon::sample {

// The whole phase-up: CP0 x10, CP1 x8, CP2 x9, CP3 x8, CP4 x16 cycles; in CP4 cycle 10
// drive 3's AT carries a wrong FCS.
wire::LineBits phase_up_4drives();

// Two clean CP4 cycles, short enough to ship as VCD and sigrok captures.
wire::LineBits cp4_excerpt();

}  // namespace sercon::sample

// How a board builds a chip: which variant, the two clock frequencies, and the levels
// of the strap pins the board ties (they become the initial levels of those pins).
#pragma once

#include <cstdint>

#include "sercon/chip/variant.hpp"

namespace sercon::chip {

struct ChipConfig {
  Variant variant = Variant::Sercon816;
  std::int64_t mclk_hz = 32'000'000;  // datasheet 3.5.1: 12..64 MHz
  std::int64_t sclk_hz = 64'000'000;  // delta spec 2.3.1: 64 MHz nominal; datasheet 3.5.2
  // Pin straps (true = tied high).
  bool sbaud = false;    // pin 29: 4 / 16 Mbit/s (0) or 2 / 8 Mbit/s (1), delta spec 2.3.1
  bool sbaud16 = false;  // pin 28: 816 mode (0) or 410B-compatible (1); SREGEN on the 410B
  bool tm0 = true;       // pins 30/31: repeater reset value and test mode (delta spec 2.3.3)
  bool tm1 = true;
  bool buswidth = true;  // pin 99: 8-bit (0) or 16-bit (1) data bus
  bool bytedir = false;  // pin 100: A0 = 0 addresses the low (0) or high (1) byte

  // Throws std::invalid_argument naming the first problem: MCLK outside 12..64 MHz, SCLK
  // above 64 MHz (or below 32 MHz with the PLL on, SBAUD16 = 0), a clock whose period is
  // not a whole number of picoseconds, SCLK not giving whole-Hz bit rates, a 410B with
  // SREGEN = 0 (external clock recovery, not modelled).
  void validate() const;
};

}  // namespace sercon::chip

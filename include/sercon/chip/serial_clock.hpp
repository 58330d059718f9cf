// The serial interface's bit rate and the SCLKO2/SCLKO4 clock outputs, from the pins and
// register bits that choose them (delta spec 2.3.1, 2.3.2; facts §5 for the 410B).
#pragma once

#include <cstdint>

#include "sercon/chip/variant.hpp"

namespace sercon::chip {

struct SerialClockSelect {
  Variant variant = Variant::Sercon816;
  std::int64_t sclk_hz = 64'000'000;
  bool sbaud = false;     // pin 29
  bool sbaud16 = false;   // pin 28 (SREGEN on the 410B: no effect on the rate)
  bool entsbaud = false;  // 1H.10
  bool swbaud = false;    // 1H.6
  bool swbaud16 = false;  // 1H.15 (816 only)
};

struct SerialClocks {
  std::int64_t bit_rate_hz = 0;  // also the TxC / RxC frequency
  std::int64_t sclko2_hz = 0;
  std::int64_t sclko4_hz = 0;
  bool compatible_mode = false;  // only 2 / 4 Mbit/s: the 410B, or the 816 with SBAUD16 = 1
};

// The table rows are stated for SCLK = 64 MHz; other SCLK frequencies scale every clock
// (the DPLL runs at 16x the bit rate from SCLK, or from the 4x PLL when SBAUD16 = 0).
constexpr SerialClocks serial_clocks(const SerialClockSelect& s) {
  SerialClocks out;
  out.compatible_mode = s.variant == Variant::Sercon410B || s.sbaud16;
  // "Slow" picks the lower rate of a pair: SBAUD pin, or SWBAUD when ENTSBAUD = 1.
  const bool slow = s.entsbaud ? s.swbaud : s.sbaud;
  // The 2/4 pair: compatible mode, or the 816 with ENTSBAUD = 1 and SWBAUD16 = 1.
  const bool low_pair = out.compatible_mode || (s.entsbaud && s.swbaud16);
  const std::int64_t divider = low_pair ? (slow ? 32 : 16) : (slow ? 8 : 4);
  out.bit_rate_hz = s.sclk_hz / divider;
  // SCLKO2 = SCLK / 2 or / 1, SCLKO4 = SCLK / 4 or / 2 (delta spec 2.3.1 second table).
  const bool divided = s.variant == Variant::Sercon410B || s.sbaud16;
  out.sclko2_hz = divided ? s.sclk_hz / 2 : s.sclk_hz;
  out.sclko4_hz = divided ? s.sclk_hz / 4 : s.sclk_hz / 2;
  return out;
}

}  // namespace sercon::chip

// Pins TM0/TM1 and register bits TMODE2-0: the repeater's reset value and the transmit
// test generator (delta spec 2.3.3, datasheet Table 1).
#pragma once

#include <cstdint>
#include <string_view>

namespace sercon::chip {

enum class TestMode : std::uint8_t {
  None,
  ContinuousLight,  // TxD1-6 send continuous signal light
  ZeroBitStream,    // TxD1-6 send a stream of 0 bits
};

constexpr std::string_view to_string(TestMode mode) {
  return mode == TestMode::None              ? "none"
         : mode == TestMode::ContinuousLight ? "continuous light"
                                             : "zero bit stream";
}

// Delta spec 2.3.3 table: TM0 TM1 = 11 none, 00 none, 01 continuous light, 10 zero bits.
constexpr TestMode test_mode_of(bool tm0, bool tm1) {
  if (tm0 == tm1) return TestMode::None;
  return tm1 ? TestMode::ContinuousLight : TestMode::ZeroBitStream;
}

// Delta spec 2.3.3 table: REPON after reset is 0 only when TM0 = TM1 = 0.
constexpr bool repon_after_reset(bool tm0, bool tm1) { return tm0 || tm1; }

// TMODE2 (0x02 bit 11) = 1 replaces the pins by TMODE0 (bit 9) and TMODE1 (bit 10), same
// coding. `tmode` is the 3-bit field TMODE2-0.
constexpr TestMode effective_test_mode(bool tm0_pin, bool tm1_pin, std::uint16_t tmode) {
  if ((tmode & 0b100u) == 0) return test_mode_of(tm0_pin, tm1_pin);
  return test_mode_of((tmode & 0b001u) != 0, (tmode & 0b010u) != 0);
}

}  // namespace sercon::chip

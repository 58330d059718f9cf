// REPON's reset value and the test generator from pins TM0/TM1 and bits TMODE2-0
// (delta spec 2.3.3, datasheet Table 1).
#include "sercon/chip/test_mode.hpp"

#include <gtest/gtest.h>

#include "chip_fixture.hpp"

namespace sercon::chip {
namespace {

using testing::ChipOnBench;
using testing::config_410b;

constexpr std::uint16_t kRepon = 1u << 3;  // 1H.3
constexpr std::uint16_t kTmode0 = 1u << 9;
constexpr std::uint16_t kTmode1 = 1u << 10;
constexpr std::uint16_t kTmode2 = 1u << 11;

ChipConfig tm_pins(bool tm0, bool tm1) {
  ChipConfig c;
  c.tm0 = tm0;
  c.tm1 = tm1;
  return c;
}

// Delta spec 2.3.3 table, row 1: TM0=1 TM1=1 -> REPON 1 (repeater on), test mode none.
TEST(Repeater, Row1BothPinsHighRepeaterOnNoTest) {
  ChipOnBench bench(tm_pins(true, true));
  EXPECT_EQ(bench.chip->reg_read(0x01) & kRepon, kRepon);
  EXPECT_EQ(bench.chip->test_mode(), TestMode::None);
}

// Row 2: TM0=0 TM1=0 -> REPON 0 (repeater off), test mode none.
TEST(Repeater, Row2BothPinsLowRepeaterOffNoTest) {
  ChipOnBench bench(tm_pins(false, false));
  EXPECT_EQ(bench.chip->reg_read(0x01) & kRepon, 0);
  EXPECT_EQ(bench.chip->test_mode(), TestMode::None);
}

// Row 3: TM0=0 TM1=1 -> REPON 1, TxD1-6 continuous signal light.
TEST(Repeater, Row3Tm0LowContinuousLight) {
  ChipOnBench bench(tm_pins(false, true));
  EXPECT_EQ(bench.chip->reg_read(0x01) & kRepon, kRepon);
  EXPECT_EQ(bench.chip->test_mode(), TestMode::ContinuousLight);
}

// Row 4: TM0=1 TM1=0 -> REPON 1, zero bit stream.
TEST(Repeater, Row4Tm1LowZeroBitStream) {
  ChipOnBench bench(tm_pins(true, false));
  EXPECT_EQ(bench.chip->reg_read(0x01) & kRepon, kRepon);
  EXPECT_EQ(bench.chip->test_mode(), TestMode::ZeroBitStream);
}

// "Configuration of pins TM0-1 determines REPON only during reset phase of the chip.
// Thereafter TM0-1 have no influence on the content of REPON."
TEST(Repeater, TmPinsAfterResetDoNotChangeRepon) {
  ChipOnBench bench(tm_pins(true, true));
  bench.chip->drive(Pin::TM0, sim::Level::Low);
  bench.chip->drive(Pin::TM1, sim::Level::Low);
  EXPECT_EQ(bench.chip->reg_read(0x01) & kRepon, kRepon);
  // ... but the test mode follows the pins at once (Table 1: "Turn on test generator").
  EXPECT_EQ(bench.chip->test_mode(), TestMode::None);
  bench.chip->drive(Pin::TM1, sim::Level::High);
  EXPECT_EQ(bench.chip->test_mode(), TestMode::ContinuousLight);
  EXPECT_EQ(bench.chip->reg_read(0x01) & kRepon, kRepon);
}

// The pins are sampled during the reset phase: changed while RSTN = 0 they count; the
// next reset (here SWRST) samples them again.
TEST(Repeater, TmPinsDuringResetSetRepon) {
  ChipOnBench bench(tm_pins(true, true));
  bench.chip->drive(Pin::RSTN, sim::Level::Low);
  bench.chip->drive(Pin::TM0, sim::Level::Low);
  bench.chip->drive(Pin::TM1, sim::Level::Low);
  EXPECT_EQ(bench.chip->reg_read(0x01) & kRepon, 0);
  bench.chip->drive(Pin::RSTN, sim::Level::High);
  EXPECT_EQ(bench.chip->reg_read(0x01) & kRepon, 0);
  bench.chip->drive(Pin::TM0, sim::Level::High);
  EXPECT_EQ(bench.chip->reg_read(0x01) & kRepon, 0);
  bench.chip->reg_write(0x01, 0x0002);  // SWRST
  EXPECT_EQ(bench.chip->reg_read(0x01) & kRepon, kRepon);
}

// REPON is a control bit: software switches the repeater whatever the pins said.
TEST(Repeater, SoftwareWritesRepon) {
  ChipOnBench bench(tm_pins(false, false));
  bench.chip->reg_write(0x01, kRepon);
  EXPECT_EQ(bench.chip->reg_read(0x01) & kRepon, kRepon);
}

// The pin-dependent reset value is an 816 addition; the 410B's REPON resets to 0
// (project decision, docs/registers.md).
TEST(Repeater, Sercon410BResetsReponToZero) {
  ChipConfig config = config_410b();
  ChipOnBench bench(config);
  EXPECT_EQ(bench.chip->reg_read(0x01) & kRepon, 0);
}

// "The control bits TMODE2-0 can also over write the actual test mode. Coding for this
// control bits does not change. TMODE2-0 has no influence to REPON."
TEST(TestModeOverride, Tmode2SelectsTmode1And0WithThePinCoding) {
  ChipOnBench bench(tm_pins(true, true));
  struct Case {
    std::uint16_t bits;
    TestMode mode;
  };
  const Case cases[] = {
      {kTmode2 | kTmode0 | kTmode1, TestMode::None},   // like TM0=1 TM1=1
      {kTmode2, TestMode::None},                       // like TM0=0 TM1=0
      {kTmode2 | kTmode1, TestMode::ContinuousLight},  // like TM0=0 TM1=1
      {kTmode2 | kTmode0, TestMode::ZeroBitStream},    // like TM0=1 TM1=0
      {kTmode0, TestMode::None},                       // TMODE2 = 0: the pins
  };
  for (const Case& c : cases) {
    bench.chip->reg_write(0x02, c.bits);
    EXPECT_EQ(bench.chip->test_mode(), c.mode) << c.bits;
    EXPECT_EQ(bench.chip->reg_read(0x01) & kRepon, kRepon);
  }
}

TEST(TestModeOverride, Tmode2ZeroLeavesThePinsInCharge) {
  ChipOnBench bench(tm_pins(true, false));
  bench.chip->reg_write(0x02, kTmode1);
  EXPECT_EQ(bench.chip->test_mode(), TestMode::ZeroBitStream);
}

}  // namespace
}  // namespace sercon::chip

// Resets: RSTN pin, software reset SWRST, OUTZ (datasheet Table 1; facts §5 for RSTFL and
// SWRST); what each keeps (RAM) and clears (registers, outputs).
#include <gtest/gtest.h>

#include "chip_fixture.hpp"

namespace sercon::chip {
namespace {

using sim::Level;
using testing::ChipOnBench;

constexpr std::uint16_t kRstfl = 0x0001;

// Dirty some registers and RAM so that a reset has something to do.
void dirty(Chip& chip) {
  chip.reg_write(0x01, 0x0020);  // REGMODE, and RSTFL cleared
  chip.reg_write(0x0A, 0x0004);  // PHAS0
  chip.reg_write(0x0F, 2000);    // TSCYC0
  chip.ram_write(0x0100, 0xCAFE);
}

void expect_reset_state(Chip& chip) {
  EXPECT_EQ(chip.reg_read(0x01) & (kRstfl | 0x0020), kRstfl);
  EXPECT_EQ(chip.reg_read(0x0A), 0);
  EXPECT_EQ(chip.reg_read(0x0F), 0);
  EXPECT_EQ(chip.ram_read(0x0100), 0xCAFE);  // RAM kept (project decision)
}

// Table 1, RSTN: "Reset, active low". The chip stays in reset while RSTN = 0.
TEST(Reset, RstnLowResetsAndHolds) {
  ChipOnBench bench;
  Chip& chip = *bench.chip;
  dirty(chip);
  chip.drive(Pin::RSTN, Level::Low);
  EXPECT_TRUE(chip.in_reset());
  EXPECT_EQ(chip.last_reset(), ResetCause::Pin);
  chip.reg_write(0x0A, 0x0002);  // ignored while held
  chip.drive(Pin::RSTN, Level::High);
  EXPECT_FALSE(chip.in_reset());
  expect_reset_state(chip);
  chip.reg_write(0x0A, 0x0002);
  EXPECT_EQ(chip.reg_read(0x0A), 0x0002);
}

// Datasheet 3.3: RSTN has an internal pull-down: an open RSTN holds the chip in reset.
TEST(Reset, FloatingRstnIsLow) {
  ChipOnBench bench;
  bench.chip->drive(Pin::RSTN, Level::HighZ);
  EXPECT_TRUE(bench.chip->in_reset());
}

// Facts §5: "SWRST (software reset: driver writes 0x0002)".
TEST(Reset, SoftwareResetThroughRegister01) {
  ChipOnBench bench;
  Chip& chip = *bench.chip;
  dirty(chip);
  chip.reg_write(0x01, 0x0002);
  EXPECT_FALSE(chip.in_reset());
  EXPECT_EQ(chip.last_reset(), ResetCause::Software);
  expect_reset_state(chip);
}

// The other bits of the write that carries SWRST are lost to the reset (project decision).
TEST(Reset, SoftwareResetWinsOverTheRestOfItsWrite) {
  ChipOnBench bench;
  bench.chip->reg_write(0x01, 0x0022);
  EXPECT_EQ(bench.chip->reg_read(0x01) & 0x0020, 0);
}

// Table 1, OUTZ: "puts all pins into a high impedance state. The clocks are turned off
// and the circuit is reset." and NDTRO "is not set to a high impedance state".
TEST(Reset, OutzFloatsEveryOutputButNdtroAndResets) {
  ChipOnBench bench;
  Chip& chip = *bench.chip;
  dirty(chip);
  chip.drive(Pin::OUTZ, Level::High);
  EXPECT_TRUE(chip.in_reset());
  EXPECT_TRUE(chip.outputs_off());
  EXPECT_EQ(chip.last_reset(), ResetCause::OutputsZ);
  for (std::size_t i = 0; i < kPinCount; ++i) {
    const Pin p = pin_at(i);
    if (pin_info(p).direction != PinDirection::Out) continue;
    if (p == Pin::NDTRO) {
      EXPECT_NE(chip.pin(p).level(), Level::HighZ);
    } else {
      EXPECT_EQ(chip.pin(p).level(), Level::HighZ) << pin_name(p);
    }
  }
  chip.drive(Pin::OUTZ, Level::Low);
  EXPECT_FALSE(chip.in_reset());
  EXPECT_EQ(chip.pin(Pin::BUSYN).level(), Level::High);
  EXPECT_EQ(chip.pin(Pin::WDOGN).level(), Level::High);
  EXPECT_EQ(chip.pin(Pin::INT0).level(), Level::Low);
  expect_reset_state(chip);
}

// An output a unit drives while OUTZ = 1 appears when OUTZ returns to 0. (DMAREQR: a pin
// its unit sets by set_output; IDLE and RECACTN are computed when read, below.)
TEST(Reset, OutputsDrivenDuringOutzAppearAfter) {
  ChipOnBench bench;
  Chip& chip = *bench.chip;
  chip.drive(Pin::OUTZ, Level::High);
  chip.set_output(Pin::DMAREQR, Level::High);
  EXPECT_EQ(chip.pin(Pin::DMAREQR).level(), Level::HighZ);
  chip.drive(Pin::OUTZ, Level::Low);
  // Leaving OUTZ is no new reset: the level set during it stays.
  EXPECT_EQ(chip.pin(Pin::DMAREQR).level(), Level::High);
}

// Datasheet Table 1: OUTZ = 1 puts every output into high impedance, also the pins computed
// when read (IDLE, RECACTN: docs/serial-and-ring.md "IDLE and RECACTN are computed when
// read"); after OUTZ they show the serial unit's state again (no telegram: both high).
TEST(Reset, LazyPinsAreHighZDuringOutzAndFollowTheUnitAfter) {
  ChipOnBench bench;
  Chip& chip = *bench.chip;
  chip.drive(Pin::OUTZ, Level::High);
  EXPECT_EQ(chip.pin(Pin::IDLE).level(), Level::HighZ);
  EXPECT_EQ(chip.pin(Pin::RECACTN).level(), Level::HighZ);
  chip.drive(Pin::OUTZ, Level::Low);
  EXPECT_EQ(chip.pin(Pin::IDLE).level(), Level::High);
  EXPECT_EQ(chip.pin(Pin::RECACTN).level(), Level::High);
}

// Datasheet 3.3: OUTZ has an internal pull-up: floating OUTZ means high impedance.
TEST(Reset, FloatingOutzIsHigh) {
  ChipOnBench bench;
  bench.chip->drive(Pin::OUTZ, Level::HighZ);
  EXPECT_TRUE(bench.chip->outputs_off());
}

// Overlapping resets: the chip leaves reset only when both RSTN = 1 and OUTZ = 0.
TEST(Reset, RstnAndOutzOverlap) {
  ChipOnBench bench;
  Chip& chip = *bench.chip;
  chip.drive(Pin::RSTN, Level::Low);
  chip.drive(Pin::OUTZ, Level::High);
  chip.drive(Pin::RSTN, Level::High);
  EXPECT_TRUE(chip.in_reset());
  chip.drive(Pin::OUTZ, Level::Low);
  EXPECT_FALSE(chip.in_reset());
}

// Every reset sets RSTFL (facts §5: "RSTFL (reset flag ...)").
TEST(Reset, EveryResetSetsRstfl) {
  ChipOnBench bench;
  Chip& chip = *bench.chip;
  EXPECT_EQ(chip.reg_read(0x01) & kRstfl, kRstfl);  // power-on
  EXPECT_EQ(chip.last_reset(), ResetCause::PowerOn);
  chip.reg_write(0x01, 0);
  chip.drive(Pin::RSTN, Level::Low);
  chip.drive(Pin::RSTN, Level::High);
  EXPECT_EQ(chip.reg_read(0x01) & kRstfl, kRstfl);
  chip.reg_write(0x01, 0);
  chip.reg_write(0x01, 0x0002);
  EXPECT_EQ(chip.reg_read(0x01) & kRstfl, kRstfl);
  chip.reg_write(0x01, 0);
  chip.drive(Pin::OUTZ, Level::High);
  chip.drive(Pin::OUTZ, Level::Low);
  EXPECT_EQ(chip.reg_read(0x01) & kRstfl, kRstfl);
}

// Power-on: RAM starts as zeros (project decision: determinism).
TEST(Reset, PowerOnRamIsZero) {
  ChipOnBench bench;
  for (std::uint16_t w = 0; w < bench.chip->ram().size(); ++w) {
    ASSERT_EQ(bench.chip->ram().read(w), 0) << w;
  }
}

// Table 1: TxD1-6 "can be switched to a high impedance state"; TXOE resets to 0, so
// after reset they float; the other outputs are inactive.
TEST(Reset, OutputsAfterResetAreInactive) {
  ChipOnBench bench;
  const Chip& chip = *bench.chip;
  for (unsigned n = 1; n <= 6; ++n) EXPECT_EQ(chip.pin(txd_pin(n)).level(), Level::HighZ);
  EXPECT_EQ(chip.pin(Pin::BUSYN).level(), Level::High);
  EXPECT_EQ(chip.pin(Pin::RECACTN).level(), Level::High);
  EXPECT_EQ(chip.pin(Pin::IDLE).level(), Level::High);
  EXPECT_EQ(chip.pin(Pin::L_ERRN).level(), Level::High);
  EXPECT_EQ(chip.pin(Pin::DMAREQR).level(), Level::Low);
  EXPECT_EQ(chip.pin(Pin::DMAREQT).level(), Level::Low);
  EXPECT_EQ(chip.pin(Pin::D0).level(), Level::HighZ);
}

}  // namespace
}  // namespace sercon::chip

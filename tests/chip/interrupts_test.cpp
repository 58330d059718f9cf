// Interrupt latches and the INT0/INT1 pins (docs/timing.md, "Interrupts"): facts §5 (0x04
// and 0x05 write-1-to-clear, 0x06..0x09 enables), datasheet Table 1 ("Interrupt sources and
// signal polarity are programmable"), delta spec 2.6 (two enable bits per interrupt).
#include <gtest/gtest.h>

#include "timing_bench.hpp"

namespace sercon::chip {
namespace {

using namespace testing;

constexpr Irq kIntStatSources[] = {
    Irq::Rdist,    Irq::Fibbr,   Irq::Cycst,   Irq::Rend,   Irq::Tend,   Irq::Rerr,   Irq::Endmk,
    Irq::MstEarly, Irq::MstLate, Irq::MstMiss, Irq::RetMst, Irq::ConClk, Irq::DivClk, Irq::DmaErr};

// Facts §5: "0x04 latched interrupt status, write 1 to clear" with INT_RDIST = 0x0001 ...
// INT_MSTMISS = 0x0200; the other bits by the register table, bit n for source n.
TEST(Interrupts, EachSourceLatchesUntilWrittenOne) {
  TimingBench b;
  for (std::size_t n = 0; n < std::size(kIntStatSources); ++n) {
    const auto bit = static_cast<std::uint16_t>(1u << n);
    b.interrupts().raise(kIntStatSources[n]);
    EXPECT_EQ(b.chip.reg_read(kIntStat), bit) << n;
    EXPECT_TRUE(b.interrupts().latched(kIntStatSources[n]));
    b.chip.reg_write(kIntStat, static_cast<std::uint16_t>(~bit));  // other bits: no effect
    EXPECT_EQ(b.chip.reg_read(kIntStat), bit) << n;
    b.chip.reg_write(kIntStat, bit);
    EXPECT_EQ(b.chip.reg_read(kIntStat), 0) << n;
  }
}

// Facts §5: "0x05 written 0xFFFF at start-up: a second write-1-to-clear status register";
// register table: bit n for service container n.
TEST(Interrupts, ServiceContainerBits) {
  TimingBench b;
  b.interrupts().raise_service_container(0);
  b.interrupts().raise_service_container(7);
  b.interrupts().raise_service_container(8);  // no such container: ignored
  EXPECT_EQ(b.chip.reg_read(kIntSc), 0x0081);
  b.chip.reg_write(kIntSc, 0x0001);
  EXPECT_EQ(b.chip.reg_read(kIntSc), 0x0080);
}

// Delta spec 2.6: "two possible enable bits, like all other interrupts have, for the
// interrupt outputs INT0 and INT1". Each INTSTAT bit is routed by its own bit of IEN0A /
// IEN1A, each INTSC bit by IEN0B / IEN1B; the pins follow every change at once.
TEST(Interrupts, RoutedSeparatelyToInt0AndInt1) {
  TimingBench b;
  PinLog int0(b.bench.scheduler, b.pin(Pin::INT0));
  b.chip.reg_write(kIen0A, kIntMstMiss);
  b.chip.reg_write(kIen1A, kIntMstEarly);
  b.interrupts().raise(Irq::MstEarly);
  EXPECT_FALSE(b.pin(Pin::INT0).high());
  EXPECT_TRUE(b.pin(Pin::INT1).high());
  b.interrupts().raise(Irq::MstMiss);
  EXPECT_TRUE(b.pin(Pin::INT0).high());
  b.chip.reg_write(kIen0A, 0);  // enable removed: pin drops at once
  EXPECT_FALSE(b.pin(Pin::INT0).high());
  b.chip.reg_write(kIen0A, kIntMstMiss);
  EXPECT_TRUE(b.pin(Pin::INT0).high());
  b.chip.reg_write(kIntStat, kIntMstMiss);  // cleared: pin drops at once
  EXPECT_FALSE(b.pin(Pin::INT0).high());
  EXPECT_TRUE(b.pin(Pin::INT1).high());
  EXPECT_EQ(int0.changes.size(), 4u);
  b.chip.reg_write(kIen0B, 0x0004);
  b.chip.reg_write(kIen1B, 0x0008);
  b.chip.reg_write(kIntStat, 0xFFFF);
  b.interrupts().raise_service_container(3);
  EXPECT_FALSE(b.pin(Pin::INT0).high());
  EXPECT_TRUE(b.pin(Pin::INT1).high());
  b.interrupts().raise_service_container(2);
  EXPECT_TRUE(b.pin(Pin::INT0).high());
}

// Datasheet Table 1: "INT0, INT1 ... Interrupts, active low or active high ... signal
// polarity [is] programmable" (INT0POL / INT1POL, 0x03).
TEST(Interrupts, ProgrammablePolarity) {
  TimingBench b;
  b.chip.reg_write(kTpCtrl, kInt0pol);
  EXPECT_TRUE(b.pin(Pin::INT0).high());  // inactive, active low
  EXPECT_FALSE(b.pin(Pin::INT1).high());
  b.chip.reg_write(kIen0A, kIntCycst);
  b.chip.reg_write(kIen1A, kIntCycst);
  b.interrupts().raise(Irq::Cycst);
  EXPECT_FALSE(b.pin(Pin::INT0).high());
  EXPECT_TRUE(b.pin(Pin::INT1).high());
  b.chip.reg_write(kTpCtrl, kInt1pol);
  EXPECT_TRUE(b.pin(Pin::INT0).high());
  EXPECT_FALSE(b.pin(Pin::INT1).high());
}

// A reset clears latches, enables and polarities: both pins inactive (low).
TEST(Interrupts, ResetDropsThePins) {
  TimingBench b;
  b.chip.reg_write(kIen0A, 0xFFFF);
  b.interrupts().raise(Irq::Rend);
  EXPECT_TRUE(b.pin(Pin::INT0).high());
  b.chip.reg_write(kSerMode, 0x0002);  // SWRST
  EXPECT_FALSE(b.pin(Pin::INT0).high());
  EXPECT_EQ(b.chip.reg_read(kIntStat), 0);
}

// OUTZ = 1 floats the pins (Chip::set_output); the level comes back afterwards.
TEST(Interrupts, PinsFloatWhileOutz) {
  TimingBench b;
  b.chip.reg_write(kIen1A, kIntCycst);
  b.chip.drive(Pin::OUTZ, Level::High);
  EXPECT_EQ(b.pin(Pin::INT1).level(), Level::HighZ);
  b.chip.drive(Pin::OUTZ, Level::Low);
  b.chip.reg_write(kIen1A, kIntCycst);
  b.interrupts().raise(Irq::Cycst);
  EXPECT_EQ(b.pin(Pin::INT1).level(), Level::High);
}

// Datasheet Table 1 (INT0 / INT1 "active low or active high ... polarity [is]
// programmable"), docs/chip.md "Resets" (every reset sets every output inactive; INTxPOL
// resets to active high) and sim/signal.hpp (watchers hear every change): an active-low
// INT0 / INT1 that is asserted (low) when the chip is reset is low after it too, now
// inactive: no change at all, not a zero-width pulse out of INTxPOL being reset before the
// latches.
TEST(Interrupts, ResetOfAnAssertedActiveLowPinIsNoPulse) {
  for (const bool by_pin : {false, true}) {
    TimingBench b;
    PinLog int0(b.bench.scheduler, b.pin(Pin::INT0));
    PinLog int1(b.bench.scheduler, b.pin(Pin::INT1));
    b.chip.reg_write(kTpCtrl, kInt0pol | kInt1pol);
    b.chip.reg_write(kIen0A, kIntRend);
    b.chip.reg_write(kIen1A, kIntRend);
    b.interrupts().raise(Irq::Rend);
    ASSERT_EQ(b.pin(Pin::INT0).level(), Level::Low);
    ASSERT_EQ(b.pin(Pin::INT1).level(), Level::Low);
    int0.changes.clear();
    int1.changes.clear();
    reset_by(b.chip, by_pin);
    EXPECT_TRUE(int0.changes.empty()) << by_pin;
    EXPECT_TRUE(int1.changes.empty()) << by_pin;
    EXPECT_EQ(b.pin(Pin::INT0).level(), Level::Low);
    EXPECT_EQ(b.pin(Pin::INT1).level(), Level::Low);
  }
}

}  // namespace
}  // namespace sercon::chip

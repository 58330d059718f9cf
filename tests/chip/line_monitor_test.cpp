// The line monitor: FIBBR ("Fibre broken: no receive signal", register table 0x02; facts
// §5 bit 13), RDIST ("receive signal distorted", bit 12), INT_RDIST / INT_FIBBR (0x04 bits
// 0, 1), L_ERRN (datasheet Table 1: "goes low when signal distortion is too high or when
// the receive signal is missing. The operating mode is programmed by the processor":
// LEDIST / LEMISS), limits RDISTLIM / FIBBRTIM (0x0D; the rules are project decisions,
// serial_unit_monitor.hpp).
#include <gtest/gtest.h>

#include <vector>

#include "sercon/chip/line_edges.hpp"
#include "serial_bench.hpp"

namespace sercon::chip {
namespace {

using sim::Level;
using sim::Time;
using testing::bit_period_of;
using testing::kFibbr;
using testing::kIntFibbr;
using testing::kIntRdist;
using testing::kIntStat;
using testing::kLedist;
using testing::kLemiss;
using testing::kLineMon;
using testing::kRdist;
using testing::kSerCtrl;
using testing::SerialBench;
using testing::telegram_bits;

bool bit(SerialBench& b, std::uint8_t reg, std::uint16_t mask) {
  return (b.chip->reg_read(reg) & mask) != 0;
}

// Runs to just before and to `t` and checks that `mask` in 0x02 rises exactly at t.
void expect_rises_at(SerialBench& b, std::uint16_t mask, Time t) {
  b.run_to(t - 1);
  EXPECT_FALSE(bit(b, kSerCtrl, mask)) << "before " << t;
  b.run_to(t);
  EXPECT_TRUE(bit(b, kSerCtrl, mask)) << "at " << t;
}

// FIBBRTIM resets to 0xFF: with nothing on RxD since release (time 0), FIBBR rises 255 bit
// times later and latches INT_FIBBR; L_ERRN stays high until LEMISS asks for it.
TEST(serial_LineMonitor, NoSignalSetsFibbrAfterFibbrtimBitTimes) {
  SerialBench b;
  const Time t = b.period();
  EXPECT_FALSE(bit(b, kIntStat, kIntFibbr));
  expect_rises_at(b, kFibbr, 255 * t);
  EXPECT_TRUE(bit(b, kIntStat, kIntFibbr));
  EXPECT_EQ(b.chip->pin(Pin::L_ERRN).level(), Level::High);
  b.chip->reg_write(kSerCtrl, kLemiss);
  EXPECT_EQ(b.chip->pin(Pin::L_ERRN).level(), Level::Low);
  // The signal comes back: FIBBR and L_ERRN clear at once, the interrupt stays latched.
  b.unit.rxd().line_condition(b.scheduler.now(), LineCondition::Idle, t);
  EXPECT_FALSE(bit(b, kSerCtrl, kFibbr));
  EXPECT_EQ(b.chip->pin(Pin::L_ERRN).level(), Level::High);
  EXPECT_TRUE(bit(b, kIntStat, kIntFibbr));
}

// A break: the line goes dark at t0; FIBBR follows FIBBRTIM bit times later. Continuous
// light has no edges either.
TEST(serial_LineMonitor, DarkOrSteadyLightForFibbrtimBitTimesIsABreak) {
  for (const LineCondition steady : {LineCondition::Dark, LineCondition::Light}) {
    SerialBench b;
    const Time t = b.period();
    b.chip->reg_write(kLineMon, 0x400A);  // FIBBRTIM = 64
    b.unit.rxd().line_condition(0, LineCondition::Idle, t);
    b.run_to(1000 * t);
    EXPECT_FALSE(bit(b, kSerCtrl, kFibbr));
    b.unit.rxd().line_condition(1000 * t, steady, 0);
    expect_rises_at(b, kFibbr, 1064 * t);
  }
}

// Decision (docs/registers.md 0x0D FIBBRTIM; docs/serial-and-ring.md, "Line monitor"): a
// healthy idle line changes level every 8 bit times, so FIBBRTIM below 8 counts as 8.
TEST(serial_LineMonitor, FibbrtimBelowEightCountsAsEight) {
  SerialBench b;
  const Time t = b.period();
  b.unit.rxd().line_condition(0, LineCondition::Idle, t);
  b.chip->reg_write(kLineMon, 0x030A);
  b.unit.rxd().line_condition(100 * t, LineCondition::Dark, 0);
  b.run_to(100 * t);
  expect_rises_at(b, kFibbr, 108 * t);
}

// Decision (docs/serial-and-ring.md, "Line monitor": "A new FIBBRTIM applies to a darkness
// already running"): writing a new FIBBRTIM while dark moves the deadline (counted from the
// last edge).
TEST(serial_LineMonitor, ANewFibbrtimAppliesToTheRunningDarkness) {
  SerialBench b;
  const Time t = b.period();
  b.unit.rxd().line_condition(0, LineCondition::Idle, t);
  b.unit.rxd().line_condition(0, LineCondition::Dark, 0);
  b.run_to(50 * t);
  b.chip->reg_write(kLineMon, 0x200A);  // 32: already passed
  EXPECT_TRUE(bit(b, kSerCtrl, kFibbr));
}

// Decision (docs/serial-and-ring.md, "Line monitor"), from facts §5 0x04: "A driver clears
// with 0xFFFF, waits 20 cycles and calls the ring closed when (reg & 0x0382) == 0" — so a
// fibre still broken must leave INT_FIBBR set after the clear. INT_FIBBR is latched from the
// FIBBR level: a write of 1 does not clear it while FIBBR is 1, and does once it is 0.
TEST(serial_LineMonitor, IntFibbrCannotBeClearedWhileTheFibreIsBroken) {
  SerialBench b;
  const Time t = b.period();
  b.run_to(300 * t);
  ASSERT_TRUE(bit(b, kSerCtrl, kFibbr));
  b.chip->reg_write(kIntStat, 0xFFFF);
  EXPECT_TRUE(bit(b, kIntStat, kIntFibbr));
  b.run_to(400 * t);
  b.chip->reg_write(kIntStat, kIntFibbr);
  EXPECT_TRUE(bit(b, kIntStat, kIntFibbr));
  // Light again: FIBBR clears, the latch stays until the host clears it, and now it can.
  b.unit.rxd().line_condition(b.scheduler.now(), LineCondition::Idle, t);
  EXPECT_FALSE(bit(b, kSerCtrl, kFibbr));
  EXPECT_TRUE(bit(b, kIntStat, kIntFibbr));
  b.chip->reg_write(kIntStat, kIntFibbr);
  EXPECT_FALSE(bit(b, kIntStat, kIntFibbr));
}

// The same decision for INT_RDIST and the RDIST level (the line monitor's other status).
TEST(serial_LineMonitor, IntRdistCannotBeClearedWhileTheSignalIsDistorted) {
  SerialBench b;
  const Time slow = bit_period_of(8);
  b.run_to(100'000);
  b.unit.rxd().line_condition(100'000, LineCondition::Idle, slow);
  b.run_to(100'000 + 20 * 8 * slow);
  ASSERT_TRUE(bit(b, kSerCtrl, kRdist));
  b.chip->reg_write(kIntStat, kIntRdist);
  EXPECT_TRUE(bit(b, kIntStat, kIntRdist));
  b.unit.rxd().line_condition(b.scheduler.now(), LineCondition::Idle, b.period());
  ASSERT_FALSE(bit(b, kSerCtrl, kRdist));
  b.chip->reg_write(kIntStat, kIntRdist);
  EXPECT_FALSE(bit(b, kIntStat, kIntRdist));
}

// Decision (serial_unit_monitor.hpp): RDISTLIM distorted edges in a row make RDIST; idle
// fill sent at 8 Mbit/s to a 16 Mbit/s receiver has an edge every 8 of its bit times, all
// distorted: with RDISTLIM = 10 (reset value) RDIST rises at the 10th edge.
TEST(serial_LineMonitor, IdleAtAnotherRateIsDistortedAfterRdistlimEdges) {
  SerialBench b;
  b.chip->reg_write(kSerCtrl, kLedist);
  const Time slow = bit_period_of(8);
  b.run_to(100'000);
  b.unit.rxd().line_condition(100'000, LineCondition::Idle, slow);
  expect_rises_at(b, kRdist, 100'000 + 9 * 8 * slow);
  EXPECT_TRUE(bit(b, kIntStat, kIntRdist));
  EXPECT_EQ(b.chip->pin(Pin::L_ERRN).level(), Level::Low);
  // The right rate again: the first clean edge clears RDIST and L_ERRN.
  b.unit.rxd().line_condition(b.scheduler.now(), LineCondition::Idle, b.period());
  EXPECT_FALSE(bit(b, kSerCtrl, kRdist));
  EXPECT_EQ(b.chip->pin(Pin::L_ERRN).level(), Level::High);
}

// A telegram at another rate: its level changes are the distorted edges; RDIST rises at
// the RDISTLIM-th one (counted here the slow way from the bits).
TEST(serial_LineMonitor, ATelegramAtAnotherRateCountsItsEdges) {
  SerialBench b;
  b.chip->reg_write(kLineMon, 0xFF05);  // RDISTLIM = 5
  const Time slow = bit_period_of(4);
  const auto bits = telegram_bits(0x33, {0x00, 0xF0, 0x0F});
  std::size_t fifth = 0;
  int edges = 0;
  for (std::size_t i = 0; i < bits->size(); ++i) {
    const bool before = i == 0 ? !bits->level(0) : bits->level(i - 1);
    if (bits->level(i) != before && ++edges == 5) {
      fifth = i;
      break;
    }
  }
  ASSERT_GT(fifth, 0u);
  EXPECT_EQ(nth_edge_bit(*bits, 5), fifth);
  b.unit.rxd().line_burst(LineBurst{0, slow, bits});
  expect_rises_at(b, kRdist, static_cast<Time>(fifth) * slow);
}

// Distorted edges are counted "in a row" across changes; a telegram at the receiver's own
// rate is a clean edge and starts the count again.
TEST(serial_LineMonitor, CleanEdgesRestartTheCount) {
  SerialBench b;
  const Time t = b.period();
  const Time slow = bit_period_of(8);
  b.chip->reg_write(kLineMon, 0xFF04);                        // RDISTLIM = 4
  b.unit.rxd().line_condition(0, LineCondition::Idle, slow);  // edges at 0, 8, 16 slow bits
  b.unit.rxd().line_burst(LineBurst{17 * slow, t, telegram_bits(1, {2})});
  b.run_to(17 * slow);
  EXPECT_FALSE(bit(b, kSerCtrl, kRdist));
  b.unit.rxd().line_condition(4 * 17 * slow, LineCondition::Idle, slow);
  b.run_to(4 * 17 * slow + 3 * 8 * slow - 1);
  EXPECT_FALSE(bit(b, kSerCtrl, kRdist));
  b.run_to(4 * 17 * slow + 3 * 8 * slow);
  EXPECT_TRUE(bit(b, kSerCtrl, kRdist));
}

// A rate change judges what RxD carries from then on at the new rate: its edges after the
// change, where the signal has them. Idle fill at 16 Mbit/s has its level changes every 8 of
// its bit times from its start; the receiver switched to 8 Mbit/s half-way between two of
// them counts the next one as the first distorted edge, not the moment of the change (no
// edge is there). RDISTLIM = 1.
TEST(serial_LineMonitor, ARateChangeCountsTheEdgesTheSignalHasAfterIt) {
  SerialBench b;  // 16 Mbit/s
  const Time t = b.period();
  b.chip->reg_write(kLineMon, 0xFF01);
  b.unit.rxd().line_condition(0, LineCondition::Idle, t);  // edges at 0, 8t, 16t, ...
  const Time change = 8 * 8 * t + 4 * t;
  b.run_to(change);
  b.chip->drive(Pin::SBAUD, Level::High);  // 8 Mbit/s (delta spec 2.3.1 table)
  ASSERT_EQ(b.period(), bit_period_of(8));
  EXPECT_FALSE(bit(b, kSerCtrl, kRdist));
  expect_rises_at(b, kRdist, 9 * 8 * t);
}

// The same for a telegram at the old rate still coming in: its own level changes after the
// change are the distorted edges. RDISTLIM = 2: RDIST rises at the second level change
// after the change.
TEST(serial_LineMonitor, ARateChangeCountsTheRestOfATelegramsEdges) {
  SerialBench b;
  const Time t = b.period();
  b.chip->reg_write(kLineMon, 0xFF02);
  const auto bits = telegram_bits(0x33, {0x00, 0xF0, 0x0F});
  b.unit.rxd().line_burst(LineBurst{0, t, bits});
  const Time change = 20 * t + 7;
  b.run_to(change);
  b.chip->drive(Pin::SBAUD, Level::High);
  std::size_t second = 0;
  int edges = 0;
  for (std::size_t i = 21; i < bits->size(); ++i) {  // line bit 21 starts after the change
    if (bits->level(i) != bits->level(i - 1) && ++edges == 2) {
      second = i;
      break;
    }
  }
  ASSERT_GT(second, 0u);
  expect_rises_at(b, kRdist, static_cast<Time>(second) * t);
}

// Decision (docs/registers.md 0x0D RDISTLIM: "0 counts as 1"): the first distorted edge.
TEST(serial_LineMonitor, RdistlimZeroCountsAsOne) {
  SerialBench b;
  b.chip->reg_write(kLineMon, 0xFF00);
  b.run_to(1000);
  b.unit.rxd().line_condition(1000, LineCondition::ZeroBits, bit_period_of(2));
  EXPECT_TRUE(bit(b, kSerCtrl, kRdist));
}

// Datasheet Table 1 L_ERRN ("The operating mode is programmed by the processor") and
// docs/registers.md 0x02 LEDIST / LEMISS: L_ERRN = !((RDIST & LEDIST) | (FIBBR & LEMISS)),
// each cause only counts when enabled.
TEST(serial_LineMonitor, LineErrorPinFollowsTheEnabledCauses) {
  SerialBench b;
  const Time t = b.period();
  b.run_to(300 * t);  // FIBBR (no signal)
  ASSERT_TRUE(bit(b, kSerCtrl, kFibbr));
  b.chip->reg_write(kSerCtrl, kLedist);
  EXPECT_EQ(b.chip->pin(Pin::L_ERRN).level(), Level::High);
  b.chip->reg_write(kSerCtrl, kLemiss);
  EXPECT_EQ(b.chip->pin(Pin::L_ERRN).level(), Level::Low);
  b.chip->reg_write(kSerCtrl, 0);
  EXPECT_EQ(b.chip->pin(Pin::L_ERRN).level(), Level::High);
}

// docs/serial-and-ring.md, "Line monitor" (FIBBR counted "from release if it was steady
// then") and docs/chip.md "Resets" (every reset loads the reset values, FIBBR 0): a reset
// clears RDIST / FIBBR; the monitor starts again at release.
TEST(serial_LineMonitor, ResetStartsTheMonitorAgain) {
  SerialBench b;
  const Time t = b.period();
  b.run_to(300 * t);
  ASSERT_TRUE(bit(b, kSerCtrl, kFibbr));
  b.chip->software_reset();
  EXPECT_FALSE(bit(b, kSerCtrl, kFibbr));
  expect_rises_at(b, kFibbr, 300 * t + 255 * t);
}

}  // namespace
}  // namespace sercon::chip

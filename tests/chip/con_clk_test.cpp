// The CON_CLK output: datasheet Table 1 ("becomes active within a communication cycle.
// Time, polarity and width are programmable"), registers 1AH..1CH (docs/timing.md,
// "CON_CLK"), exact edges.
#include <gtest/gtest.h>

#include "timing_bench.hpp"

namespace sercon::chip {
namespace {

using namespace testing;

constexpr std::int64_t kP = 32;
constexpr std::int64_t kStartDelay = 5;
constexpr std::int64_t kStartValue = 3;
constexpr std::int64_t kCycle = 250;

struct ConClkBench : TimingBench {
  ConClkBench() : pin_log(bench.scheduler, pin(Pin::CON_CLK)) {
    chip.reg_write(kClockDiv, kStartDelay << 8 | (kP - 1));
    chip.reg_write(kTcntst, kStartValue);
    chip.reg_write(kTscyc0, kCycle);
  }
  void start_master() { chip.reg_write(kSerMode, kRegmode); }  // cycles at k * 250 µs
  Time at_cycle_time(std::int64_t k, std::int64_t c) const {
    return k * kCycle * kMicrosecond + (kStartDelay + (c - kStartValue) * kP) * mclk();
  }
  PinLog pin_log;
};

// Register table 1AH TCONCLK "CON_CLK active from this cycle time (µs)", 1BH WCONCLK
// "active width (µs)"; INT_CONCLK "CON_CLK became active".
TEST(ConClk, ActiveFromTconclkForWconclkMicroseconds) {
  ConClkBench b;
  b.chip.reg_write(kTconclk, 30);
  b.chip.reg_write(kWconclk, 5);
  b.start_master();
  b.run_to(b.at_cycle_time(0, 30) - 1);
  EXPECT_FALSE(b.flags_at(b.now(), kIntConclk));
  EXPECT_TRUE(b.flags_at(b.at_cycle_time(0, 30), kIntConclk));
  b.run_to(3 * kCycle * kMicrosecond - 1);
  std::vector<PinLog::Change> expected;
  for (std::int64_t k = 0; k < 3; ++k) {
    expected.push_back({b.at_cycle_time(k, 30), Level::High});
    expected.push_back({b.at_cycle_time(k, 30) + 5 * kMicrosecond, Level::Low});
  }
  EXPECT_EQ(b.pin_log.changes, expected);
}

// sercon.h: "a pin callback may read and write registers, RAM and pins". An INT0 handler
// for INT_CONCLK ("CON_CLK became active") finds CON_CLK active.
TEST(ConClk, Int0CallbackSeesConClkActive) {
  ConClkBench b;
  b.chip.reg_write(kTconclk, 30);
  b.chip.reg_write(kWconclk, 5);
  b.chip.reg_write(kIen0A, kIntConclk);
  std::vector<Level> seen;
  b.pin(Pin::INT0).watch([&b, &seen](Level level) {
    if (level != Level::High) return;
    seen.push_back(b.pin(Pin::CON_CLK).level());
    b.chip.reg_write(kIntStat, kIntConclk);  // acknowledge
  });
  b.start_master();
  b.run_to(2 * kCycle * kMicrosecond - 1);
  EXPECT_EQ(seen, (std::vector<Level>{Level::High, Level::High}));
}

// Register table WCONCLK: "0 = never".
TEST(ConClk, WidthZeroNever) {
  ConClkBench b;
  b.chip.reg_write(kTconclk, 30);
  b.start_master();
  b.run_to(2 * kMillisecond);
  EXPECT_TRUE(b.pin_log.changes.empty());
  EXPECT_FALSE(b.flags_at(b.now(), kIntConclk));
}

// Register table 1CH POLCONCLK: "CON_CLK 1-active (0) or 0-active (1)"; the idle level
// follows at once.
TEST(ConClk, PolarityZeroActive) {
  ConClkBench b;
  b.chip.reg_write(kTconclk, 30);
  b.chip.reg_write(kWconclk, 2);
  b.start_master();
  b.write_at(kMicrosecond, kConCtrl, 1);
  b.run_to(kCycle * kMicrosecond - 1);
  EXPECT_EQ(b.pin_log.changes, (std::vector<PinLog::Change>{
                                   {kMicrosecond, Level::High},
                                   {b.at_cycle_time(0, 30), Level::Low},
                                   {b.at_cycle_time(0, 30) + 2 * kMicrosecond, Level::High}}));
}

// Decision: a start at or after the cycle time TSCYC is outside the cycle: never.
TEST(ConClk, StartBeyondTheCycleNever) {
  ConClkBench b;
  b.chip.reg_write(kTconclk, kCycle);
  b.chip.reg_write(kWconclk, 2);
  b.start_master();
  b.run_to(2 * kMillisecond);
  EXPECT_TRUE(b.pin_log.changes.empty());
}

// Decision: a width beyond the next start keeps the output active (restarted each cycle):
// one edge, INT_CONCLK in every cycle.
TEST(ConClk, WidthLongerThanTheCycleStaysActive) {
  ConClkBench b;
  b.chip.reg_write(kTconclk, 30);
  b.chip.reg_write(kWconclk, 300);
  b.start_master();
  b.run_to(b.at_cycle_time(1, 30) - 1);
  b.clear_flags();
  EXPECT_TRUE(b.flags_at(b.at_cycle_time(1, 30), kIntConclk));
  b.run_to(b.at_cycle_time(3, 30) - 1);
  EXPECT_EQ(b.pin_log.changes,
            (std::vector<PinLog::Change>{{b.at_cycle_time(0, 30), Level::High}}));
}

// Exactly back to back (width = TSCYC): no zero-width gap at the joint.
TEST(ConClk, WidthOfOneCycleHasNoGap) {
  ConClkBench b;
  b.chip.reg_write(kTconclk, 30);
  b.chip.reg_write(kWconclk, kCycle);
  b.start_master();
  b.run_to(b.at_cycle_time(4, 29));
  EXPECT_EQ(b.pin_log.changes,
            (std::vector<PinLog::Change>{{b.at_cycle_time(0, 30), Level::High}}));
}

// Register table WCONCLK "active width (µs); 0 = never", and docs/timing.md "CON_CLK"
// (decision): TCONCLK and WCONCLK are taken at the cycle start, writes act from the next
// one. A 0 written after the start leaves that cycle's pulse whole (no zero-width pulse,
// no INT_CONCLK without one) and stops the next; a new width also waits for the next cycle.
TEST(ConClk, WidthWrittenWithinACycleActsFromTheNextStart) {
  ConClkBench b;
  b.chip.reg_write(kTconclk, 30);
  b.chip.reg_write(kWconclk, 5);
  b.start_master();
  b.write_at(10 * kMicrosecond, kWconclk, 0);
  b.write_at((kCycle + 10) * kMicrosecond, kWconclk, 7);  // cycle 1
  b.clear_flags();
  EXPECT_FALSE(b.flags_at(b.at_cycle_time(2, 30) - 1, kIntConclk));
  b.run_to(b.at_cycle_time(2, 30) + 20 * kMicrosecond);
  EXPECT_EQ(b.pin_log.changes,
            (std::vector<PinLog::Change>{{b.at_cycle_time(0, 30), Level::High},
                                         {b.at_cycle_time(0, 30) + 5 * kMicrosecond, Level::Low},
                                         {b.at_cycle_time(2, 30), Level::High},
                                         {b.at_cycle_time(2, 30) + 7 * kMicrosecond, Level::Low}}));
}

// Register table POLCONCLK (resets to 0: "CON_CLK 1-active") and docs/chip.md "Resets"
// (every reset sets every output inactive): a reset while an active-low CON_CLK is active
// leaves it low, now the idle level: no change at all, not a zero-width pulse out of the
// polarity being reset while the output was still active.
TEST(ConClk, ResetWhileActiveLowIsNoPulse) {
  for (const bool by_pin : {false, true}) {
    ConClkBench b;
    b.chip.reg_write(kTconclk, 30);
    b.chip.reg_write(kWconclk, 5);
    b.chip.reg_write(kConCtrl, 1);
    b.start_master();
    b.run_to(b.at_cycle_time(0, 30) + kMicrosecond);  // active
    ASSERT_EQ(b.pin(Pin::CON_CLK).level(), Level::Low);
    b.pin_log.changes.clear();
    reset_by(b.chip, by_pin);
    b.run_to(2 * kCycle * kMicrosecond);
    EXPECT_TRUE(b.pin_log.changes.empty()) << by_pin;
    EXPECT_EQ(b.pin(Pin::CON_CLK).level(), Level::Low);
  }
}

}  // namespace
}  // namespace sercon::chip

// Master cycle start (REGMODE = 1): internal timer (PRESYNC = 0) or CYC_CLK (PRESYNC = 1),
// the MST TCYCSTART µs later, INT_CYCST, and the JTSCYC window on CYC_CLK (facts §5; delta
// spec 2.6.5; docs/timing.md, "Cycle start" and "Windows").
#include <gtest/gtest.h>

#include "timing_bench.hpp"

namespace sercon::chip {
namespace {

using namespace testing;

// 32 MHz MCLK, 1 µs tick (P = 32 periods), TCNTST = 3, MCLKST = 5, TSCYC0 = 250 µs, and
// the driver's window JTSCYC1/2 = TCNTST -/+ 7 = -4 (0xFFFC) / 10.
constexpr std::int64_t kP = 32;
constexpr std::int64_t kStartDelay = 5;  // MCLKST
constexpr std::int64_t kStartValue = 3;  // TCNTST
constexpr std::int64_t kCycle = 250;     // TSCYC0
constexpr std::int64_t kJ1 = -4;
constexpr std::int64_t kJ2 = 10;

struct MasterBench : TimingBench {
  explicit MasterBench(std::uint16_t tcycstart = 0) {
    chip.reg_write(kClockDiv, kStartDelay << 8 | (kP - 1));
    chip.reg_write(kTcntst, kStartValue);
    chip.reg_write(kTscyc0, kCycle);
    chip.reg_write(kTcycstart, tcycstart);
    chip.reg_write(kJtscyc1, static_cast<std::uint16_t>(kJ1));
    chip.reg_write(kJtscyc2, kJ2);
    cycles().on_send_mst([this] { msts.push_back(now()); });
  }
  // Counter loaded with TCNTST at `start`: it steps into value v (> TCNTST) here.
  Time step_into(Time start, std::int64_t v) const {
    return start + (kStartDelay + (v - kStartValue - 1) * kP) * mclk();
  }
  // A CYC_CLK rising edge at x starts a cycle 2 MCLK edges after the first edge >= x.
  Time cyc_clk_start(Time x) const { return edge_at_or_after(x, mclk()) + 2 * mclk(); }
  // A 2 µs high pulse, then time runs on 50 µs (past the MST of the cycle it starts).
  void cyc_clk_pulse_at(Time x) {
    run_to(x);
    chip.drive(Pin::CYC_CLK, Level::High);
    run_to(x + 2 * kMicrosecond);
    chip.drive(Pin::CYC_CLK, Level::Low);
    run_to(x + 50 * kMicrosecond);
  }
  std::vector<Time> msts;
};

// Register table PRESYNC = 0: "cycles start ... [from] the internal TSCYC timer"; facts §5:
// TSCYC0 is the cycle time in µs. The first cycle starts at the MCLK edge after REGMODE is
// written (decision), then every TSCYC0 µs exactly; the MST is due at each start
// (TCYCSTART = 0) and raises INT_CYCST.
TEST(MasterTimer, CyclesEveryTscycMicroseconds) {
  MasterBench b;
  const Time written = 3 * kMicrosecond + 1234;
  b.write_at(written, kSerMode, kRegmode);
  const Time first = edge_at_or_after(written, b.mclk());
  b.run_to(first + 10 * kCycle * kMicrosecond - 1);
  ASSERT_EQ(b.msts.size(), 10u);
  for (std::size_t k = 0; k < b.msts.size(); ++k) {
    EXPECT_EQ(b.msts[k], first + static_cast<Time>(k) * kCycle * kMicrosecond) << k;
  }
  EXPECT_TRUE(b.flags_at(b.now(), kIntCycst));
  EXPECT_EQ(b.chip.reg_read(kIntStat) & kWindowFlags, 0);  // the timer is never off-window
}

// Brief / facts §5 TCYCSTART: "Master: µs from cycle start (timer or CYC_CLK) to sending
// the MST". INT_CYCST comes with the MST, not with the cycle start.
TEST(MasterTimer, MstTcycstartMicrosecondsAfterCycleStart) {
  MasterBench b(40);
  b.write_at(0, kSerMode, kRegmode);  // cycle starts at 0, 250 µs, ...
  for (std::int64_t k = 0; k < 4; ++k) {
    const Time mst = (k * kCycle + 40) * kMicrosecond;
    b.clear_flags();
    EXPECT_FALSE(b.flags_at(mst - 1, kIntCycst)) << k;
    EXPECT_TRUE(b.flags_at(mst, kIntCycst)) << k;
    ASSERT_EQ(b.msts.size(), static_cast<std::size_t>(k + 1));
    EXPECT_EQ(b.msts.back(), mst);
  }
}

// Brief: the master's counter is loaded with TCNTST at its own cycle start, its divider
// restarted from MCLKST.
TEST(MasterTimer, CounterLoadedAtCycleStart) {
  MasterBench b;
  b.write_at(100 * kMicrosecond, kSerMode, kRegmode);
  const Time start = 100 * kMicrosecond;
  EXPECT_EQ(b.read_at(start, kTcnt), kStartValue);
  EXPECT_EQ(b.read_at(b.step_into(start, kStartValue + 1) - 1, kTcnt), kStartValue);
  EXPECT_EQ(b.read_at(b.step_into(start, kStartValue + 1), kTcnt), kStartValue + 1);
  EXPECT_EQ(b.read_at(b.step_into(start, 200), kTcnt), 200);
  EXPECT_EQ(b.read_at(start + kCycle * kMicrosecond, kTcnt), kStartValue);  // next cycle
}

// Facts §5: TSCYC1 is the cycle time in phases 3..4 (PHAS0 low bits). The timer takes the
// cycle time at each cycle start.
TEST(MasterTimer, PhaseThreeUsesTscyc1FromTheNextCycle) {
  MasterBench b;
  b.chip.reg_write(kTscyc1, 100);
  b.write_at(0, kSerMode, kRegmode);
  b.write_at(10 * kMicrosecond, kPhase, 3);
  b.run_to(600 * kMicrosecond);
  ASSERT_GE(b.msts.size(), 4u);
  EXPECT_EQ(b.msts[0], 0);
  EXPECT_EQ(b.msts[1], 250 * kMicrosecond);  // the running cycle keeps TSCYC0
  EXPECT_EQ(b.msts[2], 350 * kMicrosecond);
  EXPECT_EQ(b.msts[3], 450 * kMicrosecond);
}

// Bad input (decision): TSCYC = 0 leaves the timer idle (no cycle, no MST); programming a
// cycle time then starts a cycle at the next MCLK edge. A real driver writes REGMODE before
// the timing registers (facts §5, start-up sequence).
TEST(MasterTimer, ZeroCycleTimeIdlesUntilProgrammed) {
  MasterBench b;
  b.chip.reg_write(kTscyc0, 0);
  b.write_at(0, kSerMode, kRegmode);
  b.run_to(kMillisecond);
  EXPECT_TRUE(b.msts.empty());
  const Time programmed = kMillisecond + 100;
  b.write_at(programmed, kTscyc0, 100);
  b.run_to(kMillisecond + 350 * kMicrosecond);
  const Time first = edge_at_or_after(programmed, b.mclk());
  ASSERT_EQ(b.msts.size(), 4u);
  EXPECT_EQ(b.msts[0], first);
  EXPECT_EQ(b.msts[3], first + 300 * kMicrosecond);
}

// Decision: a cycle sends one MST; TCYCSTART >= TSCYC means the next cycle starts first and
// the MST is dropped (defined, no event storm).
TEST(MasterTimer, TcycstartBeyondTheCycleSendsNoMst) {
  MasterBench b(300);
  b.write_at(0, kSerMode, kRegmode);
  b.run_to(10 * kMillisecond);
  EXPECT_TRUE(b.msts.empty());
  EXPECT_LE(b.bench.scheduler.pending_count(), 4u);
}

// Decision (docs/timing.md, "Master with the internal timer"): a cycle sends at most one MST
// and TCYCSTART >= TSCYC drops it. At TCYCSTART = TSCYC the MST would be due at the very
// instant the next cycle starts: that start comes first and no MST goes out, also after an
// MCLKDIV change has moved both events (whatever the order of equal-time events).
TEST(MasterTimer, TcycstartEqualToTscycSendsNoMst) {
  for (const bool divider_change : {false, true}) {
    MasterBench b(kCycle);
    b.write_at(0, kSerMode, kRegmode);
    if (divider_change) {
      b.write_at(10 * kMicrosecond, kClockDiv, kStartDelay << 8 | (kP / 2 - 1));
      b.write_at(20 * kMicrosecond, kClockDiv, kStartDelay << 8 | (kP - 1));
    }
    b.run_to(5 * kMillisecond);
    EXPECT_TRUE(b.msts.empty()) << divider_change;
    EXPECT_FALSE(b.flags_at(b.now(), kIntCycst)) << divider_change;
  }
}

// Leaving master mode stops the timer.
TEST(MasterTimer, SlaveModeStopsTheTimer) {
  MasterBench b;
  b.write_at(0, kSerMode, kRegmode);
  b.write_at(300 * kMicrosecond, kSerMode, 0);
  b.run_to(2 * kMillisecond);
  EXPECT_EQ(b.msts.size(), 2u);
}

// Bad input: a cycle time of one MCLK period (MCLKDIV = 0, TSCYC = 1) is defined and
// advances time: one cycle per MCLK period.
TEST(MasterTimer, ShortestCycleIsOneMclkPeriod) {
  MasterBench b;
  b.chip.reg_write(kClockDiv, 0);
  b.chip.reg_write(kTscyc0, 1);
  b.write_at(0, kSerMode, kRegmode);
  b.run_to(100 * b.mclk() - 1);
  EXPECT_EQ(b.msts.size(), 100u);
}

// --- CYC_CLK (PRESYNC = 1) --------------------------------------------------------------

// Delta spec 2.6.5: "Being set to master mode, the input CYC_CLK is synchronizing the start
// of one or more SERCOS cycles." Each active edge (CYCPOL = 0: rising) starts a cycle after
// a two-flip-flop synchroniser; no CYC_CLK, no cycle.
TEST(MasterCycClk, RisingEdgeStartsTheCycle) {
  MasterBench b(20);
  b.write_at(0, kSerMode, kRegmode | kPresync);
  b.run_to(kMillisecond);
  EXPECT_TRUE(b.msts.empty());
  const Time x = kMillisecond + 5000;
  b.cyc_clk_pulse_at(x);
  ASSERT_EQ(b.msts.size(), 1u);
  const Time start = b.cyc_clk_start(x);
  EXPECT_EQ(b.msts[0], start + 20 * kMicrosecond);
  EXPECT_EQ(b.read_at(b.step_into(start, 60), kTcnt), 60);  // loaded at `start`
}

// Register table CYCPOL: "CYC_CLK active edge: rising (0) or falling (1)".
TEST(MasterCycClk, CycpolSelectsTheFallingEdge) {
  MasterBench b;
  b.chip.reg_write(kTpCtrl, kCycpol);
  b.write_at(0, kSerMode, kRegmode | kPresync);
  const Time x = 10 * kMicrosecond + 7;
  b.cyc_clk_pulse_at(x);  // rises at x, falls 2 µs later
  ASSERT_EQ(b.msts.size(), 1u);
  EXPECT_EQ(b.msts[0], b.cyc_clk_start(x + 2 * kMicrosecond));
}

// Facts §5: JTSCYC1/2 is the "window in which the next MST/CYC_CLK must come". Edges every
// TSCYC µs are on time: the counter, loaded with TCNTST at each start, reads TSCYC + TCNTST
// then, the middle of the driver's window TCNTST -/+ JT.
TEST(MasterCycClk, RegularEdgesRaiseNoWindowFlag) {
  MasterBench b;
  b.write_at(0, kSerMode, kRegmode | kPresync);
  for (int k = 0; k < 10; ++k) b.cyc_clk_pulse_at(kMicrosecond + k * kCycle * kMicrosecond);
  EXPECT_EQ(b.msts.size(), 10u);
  EXPECT_EQ(b.read_at(b.now(), kIntStat) & kWindowFlags, 0);
}

// Delta spec 2.6.5: "If the signal CYC_CLK is not inside this window, the interrupt MSTEARLY
// goes active." The window opens at counter value TSCYC + JTSCYC1 (signed): an edge
// recognised when the counter has just reached it is inside, one MCLK earlier is not.
TEST(MasterCycClk, WindowOpensExactlyAtTscycPlusJtscyc1) {
  for (const bool early : {false, true}) {
    MasterBench b;
    b.write_at(0, kSerMode, kRegmode | kPresync);
    b.cyc_clk_pulse_at(kMicrosecond);
    const Time start = b.cyc_clk_start(kMicrosecond);
    const Time recognised = b.step_into(start, kCycle + kJ1) - (early ? b.mclk() : 0);
    b.cyc_clk_pulse_at(recognised - 2 * b.mclk());
    EXPECT_EQ(b.msts.size(), 2u);
    EXPECT_EQ(b.msts.back(), recognised);
    EXPECT_EQ(b.flags_at(b.now(), kIntMstEarly), early) << early;
    EXPECT_EQ(b.chip.reg_read(kIntStat) & (kIntMstLate | kIntMstMiss), 0);
  }
}

// Delta spec 2.6.5: "If there no input signal CYC_CLK at all, this interrupt will not be
// set." Never an edge: no flag at all.
TEST(MasterCycClk, NoCycClkAtAllSetsNothing) {
  MasterBench b;
  b.write_at(0, kSerMode, kRegmode | kPresync);
  b.run_to(20 * kMillisecond);
  EXPECT_EQ(b.chip.reg_read(kIntStat) & (kWindowFlags | kIntCycst), 0);
}

// Brief / facts §5 "missing -> INT_MSTMISS" (decision for the master): when CYC_CLK stops,
// INT_MSTMISS is set when the counter steps out of TSCYC + JTSCYC2, MSTEARLY stays clear,
// and no MST follows (no free-wheel: the watchdog is to notice, delta spec 2.6.5).
TEST(MasterCycClk, StoppedCycClkRaisesMissAtWindowEnd) {
  MasterBench b;
  b.write_at(0, kSerMode, kRegmode | kPresync);
  b.cyc_clk_pulse_at(kMicrosecond);
  const Time start = b.cyc_clk_start(kMicrosecond);
  const Time close = b.step_into(start, kCycle + kJ2 + 1);
  EXPECT_FALSE(b.flags_at(close - 1, kIntMstMiss));
  EXPECT_TRUE(b.flags_at(close, kIntMstMiss));
  b.run_to(10 * kMillisecond);
  EXPECT_EQ(b.msts.size(), 1u);
  EXPECT_EQ(b.chip.reg_read(kIntStat) & (kIntMstEarly | kIntMstLate), 0);
}

// An edge recognised at counter TSCYC + JTSCYC2 is still inside; one that comes when the
// counter steps out of it arrives with the miss decision (decided first, whatever the
// order of equal-time events): MISS, then, as for any edge after an empty window, the
// spec's MSTEARLY ("not inside this window") and MSTLATE (decision).
TEST(MasterCycClk, WindowClosesExactlyAfterTscycPlusJtscyc2) {
  for (const bool late : {false, true}) {
    MasterBench b;
    b.write_at(0, kSerMode, kRegmode | kPresync);
    b.cyc_clk_pulse_at(kMicrosecond);
    const Time start = b.cyc_clk_start(kMicrosecond);
    const Time recognised = b.step_into(start, kCycle + kJ2 + (late ? 1 : 0));
    b.cyc_clk_pulse_at(recognised - 2 * b.mclk());
    EXPECT_EQ(b.msts.size(), 2u);
    const std::uint16_t flags = b.read_at(b.now(), kIntStat) & kWindowFlags;
    EXPECT_EQ(flags, late ? kWindowFlags : 0) << late;
  }
}

// After a missed window the next CYC_CLK restarts the cycles and is judged again from
// there: regular edges after it raise nothing new.
TEST(MasterCycClk, ResynchronisesAfterAMiss) {
  MasterBench b;
  b.write_at(0, kSerMode, kRegmode | kPresync);
  b.cyc_clk_pulse_at(kMicrosecond);
  b.cyc_clk_pulse_at(kMicrosecond + 3 * kCycle * kMicrosecond);  // two cycles skipped
  EXPECT_TRUE(b.flags_at(b.now(), kWindowFlags));
  b.clear_flags();
  for (int k = 4; k < 8; ++k) b.cyc_clk_pulse_at(kMicrosecond + k * kCycle * kMicrosecond);
  EXPECT_EQ(b.read_at(b.now(), kIntStat) & kWindowFlags, 0);
  EXPECT_EQ(b.msts.size(), 6u);
}

// The same rule with CYC_CLK: an edge whose cycle starts exactly TCYCSTART after the last
// start drops the last cycle's MST (its next cycle started first); the new cycle sends its
// own, TCYCSTART later.
TEST(MasterCycClk, CycleStartAtTheMstInstantDropsTheMst) {
  MasterBench b(100);
  b.write_at(0, kSerMode, kRegmode | kPresync);
  b.cyc_clk_pulse_at(kMicrosecond);
  const Time start = b.cyc_clk_start(kMicrosecond);
  const Time next = start + 100 * kMicrosecond;  // an MCLK edge
  b.cyc_clk_pulse_at(next - 2 * b.mclk());
  b.run_to(next + 200 * kMicrosecond);
  EXPECT_EQ(b.msts, (std::vector<Time>{next + 100 * kMicrosecond}));
}

// In CYC_CLK mode the timer does not run: edges closer than TSCYC each start a cycle.
TEST(MasterCycClk, EveryEdgeStartsACycle) {
  MasterBench b;
  b.write_at(0, kSerMode, kRegmode | kPresync);
  for (int k = 0; k < 5; ++k) b.cyc_clk_pulse_at(kMicrosecond + k * 100 * kMicrosecond);
  EXPECT_EQ(b.msts.size(), 5u);
  EXPECT_TRUE(b.flags_at(b.now(), kIntMstEarly));
}

}  // namespace
}  // namespace sercon::chip

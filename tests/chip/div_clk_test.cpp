// The DIV_CLK output: delta spec 2.7 and 2.11.1.3, datasheet Table 1 ("the pulse width is
// 1 µs"), with exact edges (docs/timing.md, "DIV_CLK").
#include <gtest/gtest.h>

#include <initializer_list>
#include <vector>

#include "sercon/chip/div_clk.hpp"
#include "timing_bench.hpp"

namespace sercon::chip {
namespace {

using namespace testing;

// Master timer at 32 MHz: cycles start at k * 250 µs; the counter is loaded with TCNTST = 3
// and steps out of cycle time c (>= 3) at start + (MCLKST + (c - 3) * 32) MCLK periods.
constexpr std::int64_t kP = 32;
constexpr std::int64_t kStartDelay = 5;
constexpr std::int64_t kStartValue = 3;
constexpr std::int64_t kCycle = 250;

struct DivClkBench : TimingBench {
  explicit DivClkBench(const ChipConfig& config = {})
      : TimingBench(config), pin_log(bench.scheduler, pin(Pin::DIV_CLK)) {
    chip.reg_write(kClockDiv, kStartDelay << 8 | (kP - 1));
    chip.reg_write(kTcntst, kStartValue);
    chip.reg_write(kTscyc0, kCycle);
  }
  void start_master() { chip.reg_write(kSerMode, kRegmode); }  // at time 0: first cycle at 0
  Time cycle_start(std::int64_t k) const { return k * kCycle * kMicrosecond; }
  Time at_cycle_time(std::int64_t k, std::int64_t c) const {
    return cycle_start(k) + (kStartDelay + (c - kStartValue) * kP) * mclk();
  }
  // The pulses expected: rising at each start, falling one µs tick later.
  std::vector<PinLog::Change> pulses(const std::vector<Time>& starts, Level active) const {
    const Level idle = active == Level::High ? Level::Low : Level::High;
    std::vector<PinLog::Change> out;
    for (Time s : starts) {
      out.push_back({s, active});
      out.push_back({s + kP * mclk(), idle});
    }
    return out;
  }
  // One mode-1 pulse at cycle time `c` of each of `cycles`, as pulses() gives them.
  std::vector<PinLog::Change> pulses_in(std::initializer_list<std::int64_t> cycles,
                                        std::int64_t c) const {
    std::vector<Time> starts;
    for (std::int64_t k : cycles) starts.push_back(at_cycle_time(k, c));
    return pulses(starts, Level::High);
  }
  PinLog pin_log;
};

// Delta spec 2.7: "The first point in time for an active output is programmed by the
// control register TDIVCLK (1EH). The distance between two pulses of DIV_CLK is determined
// by register DTDIVCLK (1FH) ... the number of pulses during one SERCOS cycle is set by
// register NDIVCLK (20H,7-0)." Table 1: "the pulse width is 1 µs".
TEST(DivClk, ModeZeroNPulsesPerCycle) {
  DivClkBench b;
  b.chip.reg_write(kTdivclk, 20);
  b.chip.reg_write(kDtdivclk, 50);
  b.chip.reg_write(kDivCtrl, 3);
  b.start_master();
  b.run_to(b.cycle_start(3) - 1);
  std::vector<Time> starts;
  for (std::int64_t k = 0; k < 3; ++k) {
    for (std::int64_t c : {20, 70, 120}) starts.push_back(b.at_cycle_time(k, c));
  }
  EXPECT_EQ(b.pin_log.changes, b.pulses(starts, Level::High));
}

// Register table INT_DIVCLK: "A DIV_CLK pulse began".
TEST(DivClk, IntDivclkAtEachPulseStart) {
  DivClkBench b;
  b.chip.reg_write(kTdivclk, 20);
  b.chip.reg_write(kDtdivclk, 50);
  b.chip.reg_write(kDivCtrl, 2);
  b.start_master();
  for (std::int64_t c : {20, 70}) {
    b.run_to(b.at_cycle_time(0, c) - 1);
    b.clear_flags();
    EXPECT_FALSE(b.flags_at(b.at_cycle_time(0, c) - 1, kIntDivclk)) << c;
    EXPECT_TRUE(b.flags_at(b.at_cycle_time(0, c), kIntDivclk)) << c;
  }
}

// sercon.h: "a pin callback may read and write registers, RAM and pins". An INT0 handler
// for INT_DIVCLK ("A DIV_CLK pulse began") finds the pulse begun.
TEST(DivClk, Int0CallbackSeesThePulseItAnnounces) {
  DivClkBench b;
  b.chip.reg_write(kTdivclk, 20);
  b.chip.reg_write(kDtdivclk, 50);
  b.chip.reg_write(kDivCtrl, 2);
  b.chip.reg_write(kIen0A, kIntDivclk);
  std::vector<Level> seen;
  b.pin(Pin::INT0).watch([&b, &seen](Level level) {
    if (level != Level::High) return;
    seen.push_back(b.pin(Pin::DIV_CLK).level());
    b.chip.reg_write(kIntStat, kIntDivclk);  // acknowledge
  });
  b.start_master();
  b.run_to(b.cycle_start(1) - 1);
  EXPECT_EQ(seen, (std::vector<Level>{Level::High, Level::High}));
}

// The other way round: a callback on the DIV_CLK pin itself finds INT_DIVCLK latched for
// the pulse it sees begin. Pin and flag change in one event; watchers hear the pin when the
// event is done (sim/signal.hpp), not between the two.
TEST(DivClk, DivClkCallbackSeesTheInterruptOfItsPulse) {
  DivClkBench b;
  b.chip.reg_write(kTdivclk, 20);
  b.chip.reg_write(kDtdivclk, 50);
  b.chip.reg_write(kDivCtrl, 2);
  std::vector<bool> latched;
  b.pin(Pin::DIV_CLK).watch([&b, &latched](Level level) {
    if (level != Level::High) return;
    latched.push_back((b.chip.reg_read(kIntStat) & kIntDivclk) != 0);
    b.chip.reg_write(kIntStat, kIntDivclk);  // acknowledge
  });
  b.start_master();
  b.run_to(b.cycle_start(1) - 1);
  EXPECT_EQ(latched, (std::vector<bool>{true, true}));
}

// Delta spec 2.7 table: "NDIVCLK 0: Never becomes active".
TEST(DivClk, NdivclkZeroNever) {
  DivClkBench b;
  b.chip.reg_write(kTdivclk, 20);
  b.start_master();
  b.run_to(5 * kMillisecond);
  EXPECT_TRUE(b.pin_log.changes.empty());
  EXPECT_FALSE(b.flags_at(b.now(), kIntDivclk));
}

// Decision (docs/timing.md): in mode 0 a pulse that would start at or after the cycle time
// TSCYC is dropped; it would fall into the next cycle.
TEST(DivClk, PulsesBeyondTheCycleAreDropped) {
  DivClkBench b;
  b.chip.reg_write(kTdivclk, 100);
  b.chip.reg_write(kDtdivclk, 50);
  b.chip.reg_write(kDivCtrl, 10);
  b.start_master();
  b.run_to(b.cycle_start(1) - 1);
  EXPECT_EQ(b.pin_log.changes,
            b.pulses({b.at_cycle_time(0, 100), b.at_cycle_time(0, 150), b.at_cycle_time(0, 200)},
                     Level::High));
}

// Delta spec 2.11.1.3: "POLDIVCLK 0: DIV_CLK pulse 1-active, 1: DIV_CLK pulse 0-active". The
// idle level follows the bit at once.
TEST(DivClk, PolarityZeroActive) {
  DivClkBench b;
  b.chip.reg_write(kTdivclk, 20);
  b.chip.reg_write(kDivCtrl, 1);
  b.start_master();
  b.write_at(kMicrosecond, kDivCtrl, kPoldivclk | 1);
  b.run_to(b.cycle_start(1) - 1);
  std::vector<PinLog::Change> expected{{kMicrosecond, Level::High}};
  for (const auto& c : b.pulses({b.at_cycle_time(0, 20)}, Level::Low)) expected.push_back(c);
  EXPECT_EQ(b.pin_log.changes, expected);
}

// Delta spec 2.7: "DIVCLKMODE 1: One time during multiple SERCOS cycles ... NDIVCLK 3:
// Active after each third cycle. The output DIV_CLK goes active the first time in the first
// SERCOS cycle (if NDIVCLK != 0)". "The control register TDIVCLK determines the point in
// time in a SERCOS cycle when DIV_CLK becomes active."
TEST(DivClk, ModeOneEveryNthCycleFromTheFirst) {
  DivClkBench b;
  b.chip.reg_write(kTdivclk, 40);
  b.chip.reg_write(kDtdivclk, 10);  // not used in mode 1
  b.chip.reg_write(kDivCtrl, kDivclkmode | 3);
  b.start_master();
  b.run_to(b.cycle_start(10) - 1);
  EXPECT_EQ(b.pin_log.changes, b.pulses_in({0, 3, 6, 9}, 40));
}

// Delta spec 2.7: "... or after the first cycle when NDIVCLK is being programmed to a value
// not equal zero." Programmed during cycle 4: nothing in cycle 4, the first pulse in
// cycle 5, then every second cycle.
TEST(DivClk, ModeOneProgrammedWhileRunning) {
  DivClkBench b;
  b.chip.reg_write(kTdivclk, 200);
  b.chip.reg_write(kDivCtrl, kDivclkmode);
  b.start_master();
  b.write_at(b.cycle_start(4) + 100 * kMicrosecond, kDivCtrl, kDivclkmode | 2);
  b.run_to(b.cycle_start(10) - 1);
  EXPECT_EQ(b.pin_log.changes, b.pulses_in({5, 7, 9}, 200));
}

// Delta spec 2.7 (DIVCLKMODE = 1): "NDIVCLK 0: Never becomes active ... The output DIV_CLK
// goes active the first time in the first SERCOS cycle (if NDIVCLK != 0) or after the first
// cycle when NDIVCLK is being programmed to a value not equal zero."
// NDIVCLK = 3 pulses in cycles 0 and 3. In cycle 1 the host stops DIV_CLK (NDIVCLK = 0) and
// programs NDIVCLK = 3 again 50 µs later: that programming restarts the sequence, so the
// first pulse comes after the first cycle, in cycle 2 (as ModeOneProgrammedWhileRunning has
// it for a programming from 0), then every third cycle: 2, 5, 8 (not the old sequence's
// 3, 6, 9, which a look at NDIVCLK at cycle starts only would keep).
TEST(DivClk, ModeOneReprogrammingWithinACycleRestartsTheSequence) {
  DivClkBench b;
  b.chip.reg_write(kTdivclk, 40);
  b.chip.reg_write(kDivCtrl, kDivclkmode | 3);
  b.start_master();
  b.write_at(b.cycle_start(1) + 100 * kMicrosecond, kDivCtrl, kDivclkmode);
  b.write_at(b.cycle_start(1) + 150 * kMicrosecond, kDivCtrl, kDivclkmode | 3);
  b.run_to(b.cycle_start(10) - 1);
  EXPECT_EQ(b.pin_log.changes, b.pulses_in({0, 2, 5, 8}, 40));
}

// Decision (docs/timing.md "DIV_CLK"): mode 0 restarts mode 1's sequence as NDIVCLK = 0
// does, also when it is chosen only for a moment within a cycle. Without the 0, a new
// NDIVCLK (3 -> 2) continues the count: the next pulse is 2 cycles after the last.
TEST(DivClk, ModeOneRestartsAfterModeZeroWithinACycleButNotOnANewCount) {
  DivClkBench b;
  b.chip.reg_write(kTdivclk, 40);
  b.chip.reg_write(kDivCtrl, kDivclkmode | 3);
  b.start_master();
  b.write_at(b.cycle_start(1) + 100 * kMicrosecond, kDivCtrl, 3);  // mode 0, no pulse planned
  b.write_at(b.cycle_start(1) + 150 * kMicrosecond, kDivCtrl, kDivclkmode | 3);
  b.write_at(b.cycle_start(2) + 100 * kMicrosecond, kDivCtrl, kDivclkmode | 2);
  b.run_to(b.cycle_start(7) - 1);
  EXPECT_EQ(b.pin_log.changes, b.pulses_in({0, 2, 4, 6}, 40));
}

// Delta spec 2.7: DIVCLKMODE is new in the 816; the 410B has mode 0 only (the bit is not
// there, so writing it changes nothing).
TEST(DivClk, The410BIgnoresDivclkmode) {
  DivClkBench b(config_410b());
  b.chip.reg_write(kTdivclk, 20);
  b.chip.reg_write(kDtdivclk, 50);
  b.chip.reg_write(kDivCtrl, kDivclkmode | 2);
  b.start_master();
  b.run_to(b.cycle_start(2) - 1);
  std::vector<Time> starts;
  for (std::int64_t k : {0, 1}) {
    for (std::int64_t c : {20, 70}) starts.push_back(b.at_cycle_time(k, c));
  }
  EXPECT_EQ(b.pin_log.changes, b.pulses(starts, Level::High));
}

// Decision (docs/timing.md §6 "DIV_CLK", mode 0): pulses 1 µs apart (DTDIVCLK = 1) join
// into one active stretch without a zero-width gap; DTDIVCLK = 0 puts all pulses on one
// instant: one pulse.
TEST(DivClk, AdjacentPulsesJoinAndCoincidentPulsesAreOne) {
  for (const int distance : {1, 0}) {
    DivClkBench b;
    b.chip.reg_write(kTdivclk, 20);
    b.chip.reg_write(kDtdivclk, static_cast<std::uint16_t>(distance));
    b.chip.reg_write(kDivCtrl, 3);
    b.start_master();
    b.run_to(b.cycle_start(1) - 1);
    const Time start = b.at_cycle_time(0, 20);
    const Time end = start + (distance == 1 ? 3 : 1) * kMicrosecond;
    EXPECT_EQ(b.pin_log.changes,
              (std::vector<PinLog::Change>{{start, Level::High}, {end, Level::Low}}))
        << distance;
  }
}

// Decision (docs/timing.md §4 "Free-wheel", §6 "DIV_CLK": planned at every cycle start,
// substitute ones included): a slave free-wheeling over missing MSTs keeps DIV_CLK going in
// the substitute cycles (they keep the µs grid); cycle times up to TSCYC + JTSCYC2 of a
// missed cycle are before the free-wheel decision and are lost in it. The counter loads at
// the third MCLK edge after the recognition (docs/timing.md §3, "Slave").
TEST(DivClk, ContinuesWhileASlaveFreeWheels) {
  DivClkBench b;
  b.chip.reg_write(kJtscyc1, static_cast<std::uint16_t>(-4));
  b.chip.reg_write(kJtscyc2, 10);
  b.chip.reg_write(kTdivclk, 100);
  b.chip.reg_write(kDivCtrl, 1);
  const Time recognised = 10 * kMicrosecond;
  b.cycles().mst_detected(recognised);  // the only MST
  const Time load = recognised + 3 * b.mclk();
  b.run_to(load + 4 * kCycle * kMicrosecond);
  std::vector<Time> starts;
  for (std::int64_t k = 0; k < 4; ++k) {
    starts.push_back(load + k * kCycle * kMicrosecond + (kStartDelay + (100 - 3) * kP) * b.mclk());
  }
  EXPECT_EQ(b.pin_log.changes, b.pulses(starts, Level::High));
}

// The unit on its own, without a Chip: scheduler, register file, signals.
TEST(DivClk, WorksWithoutAChip) {
  sim::Scheduler scheduler;
  RegisterFile regs(Variant::Sercon816);
  sim::Signal int0("INT0"), int1("INT1"), cyc_clk("CYC_CLK"), div_clk("DIV_CLK");
  const Time t = 31'250;
  TimeBase time_base(scheduler, regs, t);
  Interrupts interrupts(
      regs, [&](bool h) { int0.set(h); }, [&](bool h) { int1.set(h); });
  CycleControl cycles(time_base, interrupts, cyc_clk);
  DivClk div(time_base, interrupts, [&](bool h) { div_clk.set(h); });
  for (ChipUnit* unit : std::initializer_list<ChipUnit*>{&interrupts, &time_base, &cycles, &div}) {
    unit->reset(ResetCause::PowerOn);
  }
  for (ChipUnit* unit : std::initializer_list<ChipUnit*>{&interrupts, &time_base, &cycles, &div}) {
    unit->release();
  }
  PinLog log(scheduler, div_clk);
  regs.bus_write(kClockDiv, kStartDelay << 8 | (kP - 1));
  regs.bus_write(kTcntst, kStartValue);
  regs.bus_write(kTscyc0, kCycle);
  regs.bus_write(kTdivclk, 20);
  regs.bus_write(kDivCtrl, 1);
  regs.bus_write(kIen0A, kIntDivclk);
  regs.bus_write(kSerMode, kRegmode);
  scheduler.run_until(kCycle * kMicrosecond - 1);
  const Time start = (kStartDelay + (20 - kStartValue) * kP) * t;
  EXPECT_EQ(log.changes, (std::vector<PinLog::Change>{{start, Level::High},
                                                      {start + kMicrosecond, Level::Low}}));
  EXPECT_TRUE(int0.high());
}

// Delta spec 2.11.1.3 (POLDIVCLK resets to 0: "DIV_CLK pulse 1-active") and docs/chip.md
// "Resets" (every reset sets every output inactive): a reset in the middle of an active-low
// pulse leaves DIV_CLK low, now the idle level: no change at all, not a zero-width pulse out
// of the polarity being reset while the pulse was still on.
TEST(DivClk, ResetWithinAnActiveLowPulseIsNoPulse) {
  for (const bool by_pin : {false, true}) {
    DivClkBench b;
    b.chip.reg_write(kTdivclk, 20);
    b.chip.reg_write(kDivCtrl, kPoldivclk | 1);
    b.start_master();
    b.run_to(b.at_cycle_time(0, 20) + b.mclk());  // inside the pulse
    ASSERT_EQ(b.pin(Pin::DIV_CLK).level(), Level::Low);
    b.pin_log.changes.clear();
    reset_by(b.chip, by_pin);
    b.run_to(b.cycle_start(2));
    EXPECT_TRUE(b.pin_log.changes.empty()) << by_pin;
    EXPECT_EQ(b.pin(Pin::DIV_CLK).level(), Level::Low);
  }
}

}  // namespace
}  // namespace sercon::chip

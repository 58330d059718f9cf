// Slave cycle start (REGMODE = 0): the MST detection entry point, INT_CYCST, and the
// JTSCYC window with INT_MSTEARLY / INT_MSTLATE / INT_MSTMISS and the free-wheel on a
// missing MST (facts §5; docs/timing.md, "Cycle start" and "Windows").
#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

#include "timing_bench.hpp"

namespace sercon::chip {
namespace {

using namespace testing;

// 32 MHz MCLK, 1 µs tick, TCNTST = 3, MCLKST = 5, TSCYC0 = 250 µs, JTSCYC1/2 = TCNTST -/+
// 7 = -4 / 10 as the driver programs them.
constexpr std::int64_t kP = 32;
constexpr std::int64_t kStartDelay = 5;
constexpr std::int64_t kStartValue = 3;
constexpr std::int64_t kCycle = 250;
constexpr std::int64_t kJ1 = -4;
constexpr std::int64_t kJ2 = 10;
constexpr std::int64_t kOpens = kCycle + kJ1;   // counter value
constexpr std::int64_t kCloses = kCycle + kJ2;  // counter value

struct SlaveBench : TimingBench {
  SlaveBench() {
    chip.reg_write(kClockDiv, kStartDelay << 8 | (kP - 1));
    chip.reg_write(kTcntst, kStartValue);
    chip.reg_write(kTscyc0, kCycle);
    chip.reg_write(kJtscyc1, static_cast<std::uint16_t>(kJ1));
    chip.reg_write(kJtscyc2, kJ2);
  }
  // The receiver recognises an MST at `recognised`; the chip loads the counter at the
  // third MCLK edge after the first one at or after it. Runs to that load; returns it.
  Time mst(Time recognised) {
    run_to(recognised);
    cycles().mst_detected(recognised);
    const Time load = edge_at_or_after(recognised, mclk()) + 3 * mclk();
    run_to(load);
    return load;
  }
  // An MST whose load happens at `load`.
  Time mst_loaded_at(Time load) { return mst(load - 3 * mclk()); }
  // Counter loaded with TCNTST at `load`: it steps into value v (> TCNTST) here.
  Time step_into(Time load, std::int64_t v) const {
    return load + (kStartDelay + (v - kStartValue - 1) * kP) * mclk();
  }
  std::uint16_t window_flags() { return read_at(now(), kIntStat) & kWindowFlags; }
};

// Register table INT_CYCST: "Cycle start: MST ... accepted (slave)"; facts §5: the counter
// is loaded with TCNTST at MST detection. The first MST is not judged (nothing expected).
TEST(SlaveCycle, FirstMstLoadsTheCounterAndRaisesCycst) {
  SlaveBench b;
  const Time recognised = 100 * kMicrosecond + 1;
  b.run_to(recognised);
  b.cycles().mst_detected(recognised);
  const Time load = edge_at_or_after(recognised, b.mclk()) + 3 * b.mclk();
  EXPECT_FALSE(b.flags_at(load - 1, kIntCycst));
  EXPECT_TRUE(b.flags_at(load, kIntCycst));
  EXPECT_EQ(b.chip.reg_read(kTcnt), kStartValue);
  EXPECT_EQ(b.window_flags(), 0);
}

// Register table INT_CYCST: "Cycle start: MST ... accepted (slave)", latched at every
// accepted MST: once the host clears it, the next MST raises it again (CycleControl keeps
// "latched" as data and skips the raise while it is set).
TEST(SlaveCycle, CycstClearedComesAgainWithTheNextMst) {
  SlaveBench b;
  Time load = b.mst(100 * kMicrosecond);
  for (int k = 0; k < 3; ++k) {
    EXPECT_TRUE(b.flags_at(load, kIntCycst));
    b.chip.reg_write(kIntStat, kIntCycst);  // W1C
    EXPECT_EQ(b.chip.reg_read(kIntStat) & kIntCycst, 0);
    const Time next = load + kCycle * kMicrosecond;
    EXPECT_FALSE(b.flags_at(next - 3 * b.mclk(), kIntCycst));
    load = b.mst_loaded_at(next);
  }
  EXPECT_TRUE(b.flags_at(load, kIntCycst));
}

TEST(SlaveCycle, RegularMstsRaiseNoWindowFlag) {
  SlaveBench b;
  Time load = b.mst(100 * kMicrosecond);
  for (int k = 0; k < 20; ++k) {
    // -3, 0, +3 µs around the expected slot: inside the window -4 .. +10 µs.
    const Time jitter = (k % 3 - 1) * 3 * kMicrosecond;
    load = b.mst_loaded_at(load + kCycle * kMicrosecond + jitter);
  }
  EXPECT_EQ(b.window_flags(), 0);
}

// Facts §5: "early -> INT_MSTEARLY". The window opens at counter TSCYC + JTSCYC1 (signed):
// an MST loading when the counter has just reached it is on time, one MCLK earlier early.
// The early MST is still accepted: the counter reloads (decision).
TEST(SlaveCycle, WindowOpensExactlyAtTscycPlusJtscyc1) {
  for (const bool early : {false, true}) {
    SlaveBench b;
    const Time load = b.mst(100 * kMicrosecond);
    const Time next = b.step_into(load, kOpens) - (early ? b.mclk() : 0);
    b.mst_loaded_at(next);
    EXPECT_EQ(b.window_flags(), early ? kIntMstEarly : 0) << early;
    EXPECT_EQ(b.read_at(next, kTcnt), kStartValue);
  }
}

// Facts §5: "missing -> INT_MSTMISS". Set when the counter steps out of TSCYC + JTSCYC2.
// Decision: the chip then free-wheels: the counter moves back by TSCYC as if the MST had
// come on time, so cycle times keep their meaning; the next window closes TSCYC later.
TEST(SlaveCycle, MissingMstRaisesMissAndFreeWheels) {
  SlaveBench b;
  const Time load = b.mst(100 * kMicrosecond);
  const Time close = b.step_into(load, kCloses + 1);
  EXPECT_FALSE(b.flags_at(close - 1, kIntMstMiss));
  EXPECT_EQ(b.chip.reg_read(kTcnt), kCloses);
  EXPECT_TRUE(b.flags_at(close, kIntMstMiss));
  EXPECT_EQ(b.chip.reg_read(kTcnt), kCloses + 1 - kCycle);
  EXPECT_EQ(b.chip.reg_read(kIntStat) & (kIntMstEarly | kIntMstLate | kIntCycst), kIntCycst);
  b.clear_flags();
  // The substitute cycle keeps the µs grid: one TSCYC later the next window closes empty.
  const Time next_close = close + kCycle * kMicrosecond;
  EXPECT_FALSE(b.flags_at(next_close - 1, kIntMstMiss));
  EXPECT_TRUE(b.flags_at(next_close, kIntMstMiss));
  EXPECT_FALSE(b.flags_at(next_close, kIntCycst));  // no MST was accepted
}

// sercon.h: "a pin callback may read and write registers, RAM and pins". An INT0 handler
// for INT_MSTMISS reads the free-wheeling counter, as a read after the event does.
TEST(SlaveCycle, Int0CallbackOnAMissReadsTheSubstituteCycleCounter) {
  SlaveBench b;
  b.chip.reg_write(kIen0A, kIntMstMiss);
  std::vector<std::uint16_t> seen;
  b.pin(Pin::INT0).watch([&b, &seen](Level level) {
    if (level != Level::High) return;
    seen.push_back(b.chip.reg_read(kTcnt));
    b.chip.reg_write(kIntStat, kIntMstMiss);  // acknowledge
  });
  const Time load = b.mst(100 * kMicrosecond);
  b.run_to(b.step_into(load, kCloses + 1) + kCycle * kMicrosecond);
  const auto substitute = static_cast<std::uint16_t>(kCloses + 1 - kCycle);
  EXPECT_EQ(seen, (std::vector<std::uint16_t>{substitute, substitute}));
}

// An MST loading at counter TSCYC + JTSCYC2 is on time; one loading as the counter steps
// out of it meets the miss decision at the same instant: the miss is decided first
// (whatever the order of equal-time events), then the MST counts as late.
TEST(SlaveCycle, WindowClosesExactlyAfterTscycPlusJtscyc2) {
  for (const bool late : {false, true}) {
    SlaveBench b;
    const Time load = b.mst(100 * kMicrosecond);
    b.mst_loaded_at(b.step_into(load, kCloses + (late ? 1 : 0)));
    EXPECT_EQ(b.window_flags(), late ? (kIntMstMiss | kIntMstLate) : 0) << late;
  }
}

// The close is an event of the cycle start that expects it (Scheduler::defer_owned keeps
// that place though it enters the queue only at its time): an event due at the same instant
// and scheduled before that cycle start runs before INT_MSTMISS is raised, one scheduled
// after it runs after.
TEST(SlaveCycle, TheWindowClosesInItsPlaceAmongEventsOfItsInstant) {
  SlaveBench b;
  const Time recognised = 100 * kMicrosecond;
  const Time load = edge_at_or_after(recognised, b.mclk()) + 3 * b.mclk();
  const Time close = b.step_into(load, kCloses + 1);
  std::string seen;
  const auto note = [&](char name) {
    return [&b, &seen, name] {
      seen.push_back(name);
      seen.push_back((b.chip.reg_read(kIntStat) & kIntMstMiss) != 0 ? '+' : '-');
    };
  };
  b.bench.scheduler.at(close, note('a'));
  EXPECT_EQ(b.mst(recognised), load);
  b.bench.scheduler.at(close, note('b'));
  b.run_to(close);
  EXPECT_EQ(seen, "a-b+");
}

// Facts §5: "late -> INT_MSTLATE". Decision: an MST after its window closed empty (so after
// INT_MSTMISS) but before the substitute cycle's window opens is late; it is accepted and
// the chip is in step with the master again.
TEST(SlaveCycle, LateMstAfterTheMissIsLateAndResynchronises) {
  SlaveBench b;
  Time load = b.mst(100 * kMicrosecond);
  load = b.mst_loaded_at(load + (kCycle + 40) * kMicrosecond);
  EXPECT_EQ(b.window_flags(), kIntMstMiss | kIntMstLate);
  EXPECT_EQ(b.chip.reg_read(kTcnt), kStartValue);
  b.clear_flags();
  for (int k = 0; k < 5; ++k) load = b.mst_loaded_at(load + kCycle * kMicrosecond);
  EXPECT_EQ(b.window_flags(), 0);
}

// An MST that misses one slot but comes in the slot after is on time for the substitute
// cycle: only the miss is reported.
TEST(SlaveCycle, MstInTheSubstituteWindowIsOnTime) {
  SlaveBench b;
  const Time load = b.mst(100 * kMicrosecond);
  b.mst_loaded_at(load + 2 * kCycle * kMicrosecond);
  EXPECT_EQ(b.window_flags(), kIntMstMiss);
}

// Bad input (decision): TSCYC = 0 means no cycle time, so nothing is expected: no window,
// no flag, no free-wheel, whatever the MSTs do.
TEST(SlaveCycle, ZeroCycleTimeJudgesNothing) {
  SlaveBench b;
  b.chip.reg_write(kTscyc0, 0);
  Time load = b.mst(100 * kMicrosecond);
  load = b.mst_loaded_at(load + 17 * kMicrosecond);
  b.run_to(load + 10 * kMillisecond);
  b.mst_loaded_at(b.now() + kMicrosecond);
  EXPECT_EQ(b.window_flags(), 0);
  EXPECT_EQ(b.bench.scheduler.pending_count(), 0u);
}

// Bad input: a window that closes before the counter's start (JTSCYC2 very negative) closes
// at the first step; the free-wheel then settles at one miss per TSCYC (no storm).
TEST(SlaveCycle, WindowClosingBeforeTheCycleIsDefined) {
  SlaveBench b;
  b.chip.reg_write(kJtscyc2, static_cast<std::uint16_t>(-1000));
  b.mst(100 * kMicrosecond);
  b.run_to(20 * kMillisecond);
  EXPECT_TRUE(b.flags_at(b.now(), kIntMstMiss));
  EXPECT_LE(b.bench.scheduler.pending_count(), 2u);
}

// The entry point's contract: a time in the past is a caller error; in master mode and in
// reset an MST does not load the counter.
TEST(SlaveCycle, MstDetectedContract) {
  SlaveBench b;
  b.run_to(10 * kMicrosecond);
  EXPECT_THROW(b.cycles().mst_detected(kMicrosecond), std::invalid_argument);
  b.chip.reg_write(kSerMode, kRegmode);  // master, TSCYC0 = 250: cycle starts now
  b.run_to(20 * kMicrosecond);
  const std::uint16_t before = b.chip.reg_read(kTcnt);
  b.mst(b.now());
  EXPECT_EQ(b.read_at(b.now() + kMicrosecond, kTcnt), before + 1);
  b.chip.drive(Pin::RSTN, Level::Low);
  b.mst(b.now());
  b.run_to(b.now() + kMicrosecond);
  EXPECT_EQ(b.chip.reg_read(kIntStat) & kIntCycst, 0);
}

// docs/timing.md, "Slave": the telegram processor hears of an MST at the detection edge,
// which is the load edge (3 MCLK edges after the first at or after end + 5.5 bit), and
// passes the recognition point, by then past. Accepted while its load is not before now:
// the counter loads at that edge, not 3 edges later.
TEST(SlaveCycle, ARecognitionPastIsTakenWhileItsLoadIsNotPast) {
  SlaveBench b;
  const Time recognised = 100 * kMicrosecond + 1;
  const Time load = edge_at_or_after(recognised, b.mclk()) + 3 * b.mclk();
  b.run_to(load);
  b.cycles().mst_detected(recognised);
  EXPECT_EQ(b.read_at(load, kTcnt), kStartValue);
  EXPECT_TRUE(b.flags_at(load, kIntCycst));
  EXPECT_EQ(b.read_at(b.step_into(load, kStartValue + 1) - 1, kTcnt), kStartValue);
  EXPECT_EQ(b.read_at(b.step_into(load, kStartValue + 1), kTcnt), kStartValue + 1);
  ASSERT_GT(b.now(), load);
  EXPECT_THROW(b.cycles().mst_detected(recognised), std::invalid_argument);  // load past
}

// The telegram processor may announce a detection ahead of time; several may be in the
// synchroniser at once, and each loads the counter in turn (the second one is early).
TEST(SlaveCycle, FutureDetectionTimeIsAccepted) {
  SlaveBench b;
  b.cycles().mst_detected(10 * kMicrosecond);  // announced ahead of time
  b.cycles().mst_detected(10 * kMicrosecond + 10 * b.mclk());
  const Time load = 10 * kMicrosecond + 3 * b.mclk();
  EXPECT_EQ(b.read_at(load, kTcnt), kStartValue);
  EXPECT_EQ(b.read_at(load + 5 * b.mclk(), kTcnt), kStartValue + 1);
  EXPECT_EQ(b.read_at(load + 10 * b.mclk(), kTcnt), kStartValue);  // loaded again
  EXPECT_TRUE(b.flags_at(b.now(), kIntMstEarly));
}

}  // namespace
}  // namespace sercon::chip

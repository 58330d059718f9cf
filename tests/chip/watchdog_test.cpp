// The SERCON816 watchdog: every sentence of delta spec 2.6 and every row of the 28H..2AH
// table (2.11.2), tick-exact (docs/timing.md, "Watchdog").
#include <gtest/gtest.h>

#include <algorithm>

#include "timing_bench.hpp"

namespace sercon::chip {
namespace {

using namespace testing;

constexpr std::int64_t kP = 32;  // 32 MHz MCLK, MCLKDIV = 31: 1 µs

struct WatchdogBench : TimingBench {
  explicit WatchdogBench(const ChipConfig& config = {}) : TimingBench(config) {
    chip.reg_write(kClockDiv, kP - 1);
  }
  // Delta spec 2.6.3: T_WDOG = (MCLKDIV + 1) * TWDOG / f_MCLK.
  Time t_wdog(std::int64_t twdog) const { return kP * twdog * mclk(); }
  // Writes TWDOG, then WDOG_START at `at` keeping the R/W enables (read-modify-write, as a
  // driver does); returns the expiry time by the formula, counted from the MCLK edge that
  // registers the write.
  Time start_at(Time at, std::uint16_t twdog) {
    constexpr std::uint16_t kReadWrite =
        kEn0IntWdog | kEn1IntWdog | kWdogMsten | kEn0IntRscend | kEn1IntRscend;
    chip.reg_write(kTwdog, twdog);
    run_to(at);
    chip.reg_write(kWdCtrl, kWdogStart | (chip.reg_read(kWdCtrl) & kReadWrite));
    return edge_at_or_after(at, mclk()) + t_wdog(twdog);
  }
  bool expired_at(Time t) { return (read_at(t, kWdCtrl) & kIntWdog) != 0; }
  std::uint16_t wdctrl() { return chip.reg_read(kWdCtrl); }
  void software_reset() { chip.reg_write(kSerMode, 0x0002); }
};

// 2.6: "After chip reset the watchdog is OFF". 2.11.2: WDOG_STAT 0 = "Watchdog OFF (Reset)".
TEST(Watchdog, OffAfterReset) {
  WatchdogBench b;
  b.chip.reg_write(kTwdog, 1);
  EXPECT_EQ(b.wdctrl() & kWdogStart, 0);
  EXPECT_FALSE(b.expired_at(10 * kMillisecond));
  EXPECT_EQ(b.pin(Pin::WDOGN).level(), Level::High);
}

// 2.6: "... but can be activated by writing the control bit WDOG_START". 2.11.2:
// WDOG_START 1 = "Watchdog switch ON", WDOG_STAT 1 = "Watchdog ON".
TEST(Watchdog, WdogStartSwitchesItOn) {
  WatchdogBench b;
  b.start_at(kMicrosecond, 1000);
  EXPECT_EQ(b.wdctrl() & kWdogStart, kWdogStart);
  EXPECT_TRUE(b.watchdog().running());
}

// 2.6.3: "T_WDOG = (MCLKDIV + 1) * TWDOG / f_MCLK. After the watchdog is enabled, an internal
// down counter is preset with the value of TWDOG. The counter then counts with the given
// frequency of MCLKDIV ... Reaching the counter value 0000H, the watchdog is set." Exact to
// the picosecond for several clocks, dividers (also a non-µs one) and write phases.
TEST(Watchdog, ExpiresAfterTwdogTimesTheDividerPeriod) {
  struct Case {
    std::int64_t mhz;
    std::uint16_t mclkdiv;
    std::uint16_t twdog;
    Time written;
  };
  for (const Case c :
       {Case{32, 31, 100, 5 * kMicrosecond}, Case{25, 24, 1, 7777}, Case{64, 63, 65535, 123457},
        Case{16, 7, 300, 1}, Case{50, 49, 2, 19999}, Case{20, 0, 5, 3 * kMicrosecond + 1}}) {
    ChipConfig config;
    config.mclk_hz = c.mhz * 1'000'000;
    TimingBench b(config);
    b.chip.reg_write(kClockDiv, c.mclkdiv);
    b.chip.reg_write(kTwdog, c.twdog);
    b.write_at(c.written, kWdCtrl, kWdogStart);
    const Time expiry =
        edge_at_or_after(c.written, b.mclk()) + (c.mclkdiv + 1) * std::int64_t{c.twdog} * b.mclk();
    EXPECT_EQ(b.read_at(expiry - 1, kWdCtrl) & (kIntWdog | kWdogStart), kWdogStart) << c.mhz;
    EXPECT_EQ(b.read_at(expiry, kWdCtrl) & (kIntWdog | kWdogStart), kIntWdog) << c.mhz;
  }
}

// Decision: TWDOG = 0 is the count 0000H already: the watchdog expires at the edge that
// starts it.
TEST(Watchdog, TwdogZeroExpiresAtOnce) {
  WatchdogBench b;
  const Time expiry = b.start_at(10 * kMicrosecond + 5, 0);
  EXPECT_EQ(expiry, edge_at_or_after(10 * kMicrosecond + 5, b.mclk()));
  EXPECT_TRUE(b.expired_at(expiry));
}

// 2.6: "Once activated, not switch off is possible except by software reset." Writing 0,
// writing the other bits, or WDOG_START again changes nothing (START is no trigger).
TEST(Watchdog, CannotBeSwitchedOffByWrites) {
  WatchdogBench b;
  const Time expiry = b.start_at(kMicrosecond, 200);
  b.write_at(50 * kMicrosecond, kWdCtrl, 0x0000);
  b.write_at(60 * kMicrosecond, kWdCtrl, static_cast<std::uint16_t>(~kWdogStart));
  b.write_at(70 * kMicrosecond, kWdCtrl, kWdogStart);
  b.write_at(80 * kMicrosecond, kTwdog, 0);  // used from the next preset only
  EXPECT_EQ(b.read_at(expiry - 1, kWdCtrl) & (kWdogStart | kIntWdog), kWdogStart);
  EXPECT_TRUE(b.expired_at(expiry));
}

// 2.6 "... except by software reset", 2.6.2 "Reset ... through hardware, respectively
// software reset": SWRST and RSTN switch it off; it stays off.
TEST(Watchdog, SoftwareAndHardwareResetSwitchItOff) {
  for (const bool hardware : {false, true}) {
    WatchdogBench b;
    b.start_at(kMicrosecond, 100);
    b.run_to(50 * kMicrosecond);
    if (hardware) {
      b.chip.drive(Pin::RSTN, Level::Low);
      b.chip.drive(Pin::RSTN, Level::High);
    } else {
      b.software_reset();
    }
    EXPECT_EQ(b.wdctrl() & kWdogStart, 0) << hardware;
    EXPECT_FALSE(b.expired_at(10 * kMillisecond)) << hardware;
  }
}

// 2.6: "If the watchdog activates, it switches off automatically." 2.11.2 INT_WDOG 1 =
// "Watchdog Active". Off means: no further expiry, even after clearing the flag.
TEST(Watchdog, SwitchesOffWhenItExpires) {
  WatchdogBench b;
  const Time expiry = b.start_at(kMicrosecond, 10);
  EXPECT_EQ(b.read_at(expiry, kWdCtrl) & (kWdogStart | kIntWdog), kIntWdog);
  EXPECT_FALSE(b.watchdog().running());
  b.chip.reg_write(kWdCtrl, kIntWdog);  // CLR_INT_WDOG
  EXPECT_FALSE(b.expired_at(expiry + 10 * kMillisecond));
}

// 2.6: "The watchdog interrupt remains set until it is cleared by a reset or writing to
// CLR_INT_WDOG." 2.11.2: CLR_INT_WDOG 1 = "Clear INT_WDOG", 0 = "No Action".
TEST(Watchdog, IntWdogRemainsUntilClearedOrReset) {
  WatchdogBench b;
  const Time expiry = b.start_at(kMicrosecond, 10);
  EXPECT_TRUE(b.expired_at(expiry + 50 * kMillisecond));
  b.chip.reg_write(kWdCtrl, static_cast<std::uint16_t>(~kIntWdog & ~kWdogStart));
  EXPECT_NE(b.wdctrl() & kIntWdog, 0);
  b.chip.reg_write(kWdCtrl, kIntWdog);
  EXPECT_EQ(b.wdctrl() & kIntWdog, 0);
  // ... or by a reset.
  const Time again = b.start_at(b.now() + 1, 10);
  EXPECT_TRUE(b.expired_at(again));
  b.software_reset();
  EXPECT_EQ(b.wdctrl() & kIntWdog, 0);
}

// 2.6.3: "Each trigger even again loads the counter to the value of TWDOG." 2.6.4: "by
// writing the value 42H to the control bits WDOG_TRIG (29H,7-0)."
TEST(Watchdog, Hex42ReloadsTheCounter) {
  WatchdogBench b;
  b.start_at(kMicrosecond, 100);
  Time expiry = 0;
  for (int k = 1; k <= 5; ++k) {
    const Time trigger = k * 80 * kMicrosecond + 1111 * k;
    b.write_at(trigger, kWdTrig, 0x42);
    expiry = edge_at_or_after(trigger, b.mclk()) + b.t_wdog(100);
  }
  EXPECT_FALSE(b.expired_at(expiry - 1));
  EXPECT_TRUE(b.expired_at(expiry));
}

// 2.6.4 / 2.11.2 "WDOG_TRIG W 42H": any other value does nothing; the value is bits 7-0
// (decision: bits 15-8 of 29H are not evaluated, datasheet 4.1).
TEST(Watchdog, OnlyHex42InBits7To0Triggers) {
  for (const int value : {0x0000, 0x0041, 0x0043, 0x0024, 0x00FF, 0x4200, 0x0142}) {
    WatchdogBench b;
    const Time expiry = b.start_at(kMicrosecond, 100);
    const Time trigger = 60 * kMicrosecond;
    b.write_at(trigger, kWdTrig, static_cast<std::uint16_t>(value));
    const bool triggers = (value & 0xFF) == 0x42;
    EXPECT_EQ(b.expired_at(expiry), !triggers) << value;
    EXPECT_TRUE(b.expired_at(trigger + b.t_wdog(100))) << value;
  }
}

// On an 8-bit bus a word write is two byte cycles: the byte carrying 42H in bits 7-0
// triggers once, the other byte does nothing (register file: byte enables).
TEST(Watchdog, ByteWritesOnAnEightBitBus) {
  ChipConfig config;
  config.buswidth = false;
  WatchdogBench b(config);
  const Time expiry = b.start_at(kMicrosecond, 100);
  b.write_at(60 * kMicrosecond, kWdTrig, 0x4200);
  EXPECT_TRUE(b.expired_at(expiry));
  b.chip.reg_write(kWdCtrl, kIntWdog);
  const Time again = b.start_at(expiry + 1, 100);
  b.write_at(again - 10 * kMicrosecond, kWdTrig, 0x0042);
  EXPECT_FALSE(b.expired_at(again));
}

// 2.6.4: "Triggering by writing the control bits WDOG_TRIG is possible at any time" (also
// with MST triggering enabled in master mode); a trigger while off does not start it.
TEST(Watchdog, SoftwareTriggerAtAnyTimeButOnlyWhenOn) {
  WatchdogBench b;
  b.chip.reg_write(kTwdog, 10);
  b.write_at(kMicrosecond, kWdTrig, 0x42);
  EXPECT_FALSE(b.expired_at(kMillisecond));
  b.chip.reg_write(kWdCtrl, kWdogMsten);
  b.chip.reg_write(kSerMode, kRegmode | kPresync);  // master, no CYC_CLK: no MST
  const Time expiry = b.start_at(2 * kMillisecond, 100);
  const Time trigger = expiry - 5 * kMicrosecond;
  b.write_at(trigger, kWdTrig, 0x42);
  EXPECT_FALSE(b.expired_at(expiry));
  EXPECT_TRUE(b.expired_at(edge_at_or_after(trigger, b.mclk()) + b.t_wdog(100)));
}

// 2.6.5: "Triggering with the internal MST start signal must be enabled through the control
// bit WDOG_MSTEN." 2.11.2: "Master: Trigger via MST enabled". A master sending MSTs every
// 250 µs keeps a 300 µs watchdog alive only with WDOG_MSTEN.
TEST(Watchdog, MstStartTriggersWithWdogMstenInMasterMode) {
  for (const bool msten : {false, true}) {
    WatchdogBench b;
    b.chip.reg_write(kTscyc0, 250);
    b.chip.reg_write(kSerMode, kRegmode);  // first MST at 0, then every 250 µs
    if (msten) b.chip.reg_write(kWdCtrl, kWdogMsten);
    const Time expiry = b.start_at(10 * kMicrosecond, 300);
    EXPECT_EQ(b.expired_at(expiry), !msten) << msten;
    EXPECT_EQ(b.expired_at(20 * kMillisecond), !msten) << msten;
  }
}

// 2.6.3: "Reaching the counter value 0000H, the watchdog is set. Each trigger event again
// loads the counter to the value of TWDOG." Decision (docs/timing.md, "Watchdog"): a
// trigger at the very edge at which the count reaches 0000H loads it again (the load comes
// first), whatever the order of the equal-time events. TWDOG = TSCYC with MST triggering:
// every MST comes exactly when the count runs out, so the watchdog stays quiet while MSTs
// come (TCYCSTART = 0: the MST at the cycle start; 40: from its own alarm) and expires
// T_WDOG after the last one when they stop.
TEST(Watchdog, MstAtTheExpiryEdgeTriggersFirst) {
  for (const std::int64_t tcycstart : {0, 40}) {
    WatchdogBench b;
    b.chip.reg_write(kTscyc0, 250);
    b.chip.reg_write(kTcycstart, static_cast<std::uint16_t>(tcycstart));
    b.chip.reg_write(kWdCtrl, kWdogMsten);
    b.start_at(0, 250);
    b.chip.reg_write(kSerMode, kRegmode);  // cycles at k * 250 µs, MSTs TCYCSTART later
    const Time stop = 2 * kMillisecond + 100 * kMicrosecond;
    EXPECT_FALSE(b.expired_at(stop)) << tcycstart;
    b.chip.reg_write(kSerMode, 0);  // slave: no more MSTs
    const Time last_mst = 2 * kMillisecond + tcycstart * kMicrosecond;
    EXPECT_FALSE(b.expired_at(last_mst + b.t_wdog(250) - 1)) << tcycstart;
    EXPECT_TRUE(b.expired_at(last_mst + b.t_wdog(250))) << tcycstart;
  }
}

// 2.11.2 WDOG_MSTEN: "Slave: No Function". Received MSTs do not trigger.
TEST(Watchdog, MstDoesNotTriggerInSlaveMode) {
  WatchdogBench b;
  b.chip.reg_write(kWdCtrl, kWdogMsten);
  const Time expiry = b.start_at(kMicrosecond, 300);
  for (int k = 1; k <= 3; ++k) {
    b.run_to(k * 100 * kMicrosecond);
    b.cycles().mst_detected(b.now());
  }
  EXPECT_TRUE(b.expired_at(expiry));
}

// 2.6.5: "The watchdog is not triggered directly with the signal CYC_CLK, but by the start
// signal for the MST's caused by CYC_CLK. If the input CYC_CLK fails, the watchdog goes
// active after a certain time interval after start of the last MST." With TCYCSTART = 10 µs
// the expiry counts from the last MST, 10 µs after the last CYC_CLK cycle start.
TEST(Watchdog, CycClkFailureExpiresTwdogAfterTheLastMst) {
  WatchdogBench b;
  b.chip.reg_write(kTscyc0, 250);
  b.chip.reg_write(kTcycstart, 10);
  b.chip.reg_write(kSerMode, kRegmode | kPresync);
  b.chip.reg_write(kWdCtrl, kWdogMsten);
  b.start_at(kMicrosecond, 400);
  Time last_mst = 0;
  for (int k = 0; k < 6; ++k) {
    const Time x = 100 * kMicrosecond + k * 250 * kMicrosecond;
    b.run_to(x);
    b.chip.drive(Pin::CYC_CLK, Level::High);
    b.run_to(x + kMicrosecond);
    b.chip.drive(Pin::CYC_CLK, Level::Low);
    last_mst = edge_at_or_after(x, b.mclk()) + 2 * b.mclk() + 10 * kMicrosecond;
  }
  EXPECT_FALSE(b.expired_at(last_mst + b.t_wdog(400) - 1));
  EXPECT_TRUE(b.expired_at(last_mst + b.t_wdog(400)));
}

// 2.6.2: "ENTMT (3H.8) 0, PHAS0 (AH.0-7) 0H ... These register bits can be programmed again
// by the bus interface only after the status bit INT_WDOG is cleared."
TEST(Watchdog, ExpiryClearsAndProtectsEntmtAndPhas0) {
  WatchdogBench b;
  b.chip.reg_write(kTpCtrl, kEntmt);
  b.chip.reg_write(kPhase, 4);
  const Time expiry = b.start_at(kMicrosecond, 10);
  b.run_to(expiry);
  EXPECT_EQ(b.chip.reg_read(kTpCtrl) & kEntmt, 0);
  EXPECT_EQ(b.chip.reg_read(kPhase) & 0xFF, 0);
  b.chip.reg_write(kTpCtrl, kEntmt | kCycpol);
  b.chip.reg_write(kPhase, 3);
  EXPECT_EQ(b.chip.reg_read(kTpCtrl), kCycpol);  // only ENTMT is protected
  EXPECT_EQ(b.chip.reg_read(kPhase) & 0xFF, 0);
  b.chip.reg_write(kWdCtrl, kIntWdog);  // CLR_INT_WDOG
  b.chip.reg_write(kTpCtrl, kEntmt);
  b.chip.reg_write(kPhase, 3);
  EXPECT_EQ(b.chip.reg_read(kTpCtrl), kEntmt);
  EXPECT_EQ(b.chip.reg_read(kPhase) & 0xFF, 3);
}

// 2.6.2: "After reset of this register the SERCON816 transmits MST's of phase 0 after
// watchdog is active." A master in phase 4 (TSCYC1 = 100 µs) falls back to phase 0 and its
// cycle time TSCYC0 = 250 µs from the next cycle start.
TEST(Watchdog, MasterFallsBackToPhaseZeroCycles) {
  WatchdogBench b;
  b.chip.reg_write(kTscyc0, 250);
  b.chip.reg_write(kTscyc1, 100);
  b.chip.reg_write(kPhase, 4);
  std::vector<Time> msts;
  b.cycles().on_send_mst([&] { msts.push_back(b.now()); });
  b.chip.reg_write(kSerMode, kRegmode);  // cycles at 0, 100, 200, ... µs
  b.start_at(kMicrosecond, 450);         // expires at 451 µs
  b.run_to(kMillisecond);
  ASSERT_GE(msts.size(), 7u);
  EXPECT_EQ(msts[4], 400 * kMicrosecond);
  EXPECT_EQ(msts[5], 500 * kMicrosecond);  // the cycle that ran at expiry keeps its time
  EXPECT_EQ(msts[6], 750 * kMicrosecond);
}

// 2.6.2: "Reset of these control bits through hardware, respectively software reset has
// higher priority than reset through INT_WDOG!" After a reset ENTMT / PHAS0 are writable
// at once, whether the reset came at the very instant of expiry (before or after it in the
// scheduler's order) or later.
TEST(Watchdog, ResetHasPriorityOverTheProtection) {
  for (int order = 0; order < 3; ++order) {
    WatchdogBench b;
    const Time expiry = edge_at_or_after(kMicrosecond, b.mclk()) + b.t_wdog(10);
    if (order == 0) b.bench.scheduler.at(expiry, [&] { b.software_reset(); });
    b.start_at(kMicrosecond, 10);
    if (order == 1) b.bench.scheduler.at(expiry, [&] { b.software_reset(); });
    b.run_to(expiry + (order == 2 ? kMicrosecond : 0));
    if (order == 2) b.software_reset();
    b.chip.reg_write(kTpCtrl, kEntmt);
    b.chip.reg_write(kPhase, 2);
    EXPECT_EQ(b.chip.reg_read(kTpCtrl), kEntmt) << order;
    EXPECT_EQ(b.chip.reg_read(kPhase) & 0xFF, 2) << order;
    EXPECT_EQ(b.wdctrl() & (kIntWdog | kWdogStart), 0) << order;
  }
}

// 2.6.1: "This must be enabled through the control bit WDOOUT_EN" (2.11.2 WDOUT_SET): not
// enabled, WDOGN stays inactive (high) at expiry.
TEST(Watchdog, WdognNeedsWdoutSet) {
  WatchdogBench b;
  PinLog wdogn(b.bench.scheduler, b.pin(Pin::WDOGN));
  const Time expiry = b.start_at(kMicrosecond, 10);
  b.run_to(expiry + 10 * kMicrosecond);
  EXPECT_TRUE(wdogn.changes.empty());
}

// 2.11.2: WDOUT_SET 1 = "Set Enable Output WDOGN", WDOUT_STAT reads it (0 after reset); no
// bit clears it but a reset.
TEST(Watchdog, WdoutStatReadsBackUntilReset) {
  WatchdogBench b;
  EXPECT_EQ(b.wdctrl() & kWdoutSet, 0);
  b.chip.reg_write(kWdCtrl, kWdoutSet);
  EXPECT_EQ(b.wdctrl() & kWdoutSet, kWdoutSet);
  b.chip.reg_write(kWdCtrl, 0);
  EXPECT_EQ(b.wdctrl() & kWdoutSet, kWdoutSet);
  b.software_reset();
  EXPECT_EQ(b.wdctrl() & kWdoutSet, 0);
}

// 2.6.1: "The output WDOGN is an active '0' signal ... Time 1 µsec is given by divider
// MCLKDIV. Watchdog output then remains active for the next minimum 2, maximum 3 periods of
// this divider." Decision: low from the expiry to the third tick of the free-running µs
// divider after it, so 2 < width <= 3 periods depending on that divider's phase. The
// free-running divider ticks at MCLK edges 1 + 32 k here (MCLKDIV written at time 0, the
// tick pending then at edge 1). Every phase of the expiry against it is tried.
TEST(Watchdog, WdognLowForTwoToThreeDividerPeriods) {
  Time shortest = kMillisecond;
  Time longest = 0;
  for (std::int64_t phase = 0; phase < kP; ++phase) {
    WatchdogBench b;
    b.chip.reg_write(kWdCtrl, kWdoutSet);
    PinLog wdogn(b.bench.scheduler, b.pin(Pin::WDOGN));
    const Time t = b.mclk();
    const Time expiry = b.start_at((1000 + phase) * t, 20);
    b.run_to(expiry + 5 * kMicrosecond);
    const std::int64_t e = expiry / t;
    const std::int64_t next_tick = 1 + kP * ((e - 1) / kP + 1);  // first tick edge > e
    const Time release = (next_tick + 2 * kP) * t;
    ASSERT_EQ(wdogn.changes.size(), 2u) << phase;
    EXPECT_EQ(wdogn.changes[0], (PinLog::Change{expiry, Level::Low})) << phase;
    EXPECT_EQ(wdogn.changes[1], (PinLog::Change{release, Level::High})) << phase;
    const Time width = release - expiry;
    EXPECT_GT(width, 2 * kMicrosecond) << phase;
    EXPECT_LE(width, 3 * kMicrosecond) << phase;
    shortest = std::min(shortest, width);
    longest = std::max(longest, width);
  }
  EXPECT_EQ(shortest, 2 * kMicrosecond + 31250);
  EXPECT_EQ(longest, 3 * kMicrosecond);
}

// 2.6: "This interrupt has two possible enable bits ... for the interrupt outputs INT0 and
// INT1 (Enx_INT_WDOG)". 2.11.2: EN0_INT_WDOG "INT_WDOG triggers INT0", EN1 for INT1.
TEST(Watchdog, IntWdogRoutesToInt0AndInt1) {
  for (const std::uint16_t enable : {kEn0IntWdog, kEn1IntWdog}) {
    WatchdogBench b;
    b.chip.reg_write(kWdCtrl, enable);
    const Time expiry = b.start_at(kMicrosecond, 10);
    b.run_to(expiry - 1);
    EXPECT_EQ(b.pin(Pin::INT0).level(), Level::Low);
    b.run_to(expiry);
    EXPECT_EQ(b.pin(Pin::INT0).level(), sim::level_of(enable == kEn0IntWdog));
    EXPECT_EQ(b.pin(Pin::INT1).level(), sim::level_of(enable == kEn1IntWdog));
    b.chip.reg_write(kWdCtrl, static_cast<std::uint16_t>(enable | kIntWdog));
    EXPECT_EQ(b.pin(Pin::INT0).level(), Level::Low);
    EXPECT_EQ(b.pin(Pin::INT1).level(), Level::Low);
  }
}

// 2.11.2: the R/W bits read back; the W bits read as their status.
TEST(Watchdog, ControlBitsReadBack) {
  WatchdogBench b;
  const std::uint16_t rw = kEn0IntWdog | kEn1IntWdog | kWdogMsten | kEn0IntRscend | kEn1IntRscend;
  b.chip.reg_write(kWdCtrl, rw);
  EXPECT_EQ(b.wdctrl(), rw);
  b.chip.reg_write(kWdCtrl, 0);
  EXPECT_EQ(b.wdctrl(), 0);
  b.chip.reg_write(kTwdog, 0xBEEF);
  EXPECT_EQ(b.chip.reg_read(kTwdog), 0xBEEF);
  b.chip.reg_write(kWdTrig, 0x42);
  EXPECT_EQ(b.chip.reg_read(kWdTrig), 0);  // W: reads 0
}

// 2.10.2.2 / 2.11.2: INT_RSCEND is set by the service-container engine (entry point
// Interrupts::raise), cleared by CLR_RSCEND, routed by EN0/EN1_INT_RSCEND.
TEST(Watchdog, IntRscendLatchClearAndRoute) {
  WatchdogBench b;
  b.interrupts().raise(Irq::Rscend);
  EXPECT_EQ(b.wdctrl() & kIntRscend, kIntRscend);
  EXPECT_EQ(b.pin(Pin::INT0).level(), Level::Low);
  b.chip.reg_write(kWdCtrl, kEn0IntRscend);
  EXPECT_EQ(b.pin(Pin::INT0).level(), Level::High);
  b.chip.reg_write(kWdCtrl, kEn1IntRscend);
  EXPECT_EQ(b.pin(Pin::INT0).level(), Level::Low);
  EXPECT_EQ(b.pin(Pin::INT1).level(), Level::High);
  b.chip.reg_write(kWdCtrl, kEn1IntRscend | kIntRscend);  // CLR_RSCEND
  EXPECT_EQ(b.wdctrl() & kIntRscend, 0);
  EXPECT_EQ(b.pin(Pin::INT1).level(), Level::Low);
}

// Delta spec 1.1 / 2.6: the watchdog is new in the 816. On the 410B 28H..2AH are not there
// and nothing happens (pin 24 is TxDNRZ there, not driven by this model).
TEST(Watchdog, The410BHasNone) {
  WatchdogBench b(config_410b());
  PinLog wdogn(b.bench.scheduler, b.pin(Pin::WDOGN));
  b.chip.reg_write(kTwdog, 1);
  b.chip.reg_write(kWdCtrl, 0xFFFF);
  b.chip.reg_write(kWdTrig, 0x42);
  b.interrupts().raise(Irq::Wdog);
  b.interrupts().raise(Irq::Rscend);
  b.run_to(kMillisecond);
  EXPECT_EQ(b.chip.reg_read(kWdCtrl), 0);
  EXPECT_EQ(b.chip.reg_read(kTwdog), 0);
  EXPECT_FALSE(b.watchdog().running());
  EXPECT_TRUE(wdogn.changes.empty());
  // Delta spec 2.2: pin 24 is WDOGN on the 816 only (TxDNRZ on the 410B, not modelled):
  // the 410B does not drive it (docs/timing.md, "Watchdog").
  EXPECT_EQ(b.pin(Pin::WDOGN).level(), sim::Level::HighZ);
}

}  // namespace
}  // namespace sercon::chip

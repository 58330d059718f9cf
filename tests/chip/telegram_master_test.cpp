// The master's MST (docs/telegram-processing.md, "Master"): one MST per cycle with PHAS0
// as its data, not gated by ENTMT (delta spec 2.6.2); its return measured in TCYCDEL and
// judged against JTRDEL1/JTRDEL2 (facts §5), INT_RETMST and NMSTERR (datasheet 4.2, RAM
// word 10) when it comes back outside the window or not at all.
#include <gtest/gtest.h>

#include <array>

#include "sercon/chip/interrupts.hpp"
#include "telegram_bench.hpp"

namespace sercon::chip {
namespace {

using namespace telegram_testing;

constexpr Time kFibre = 1'000'000;  // 1 µs, on the SCLK grid
constexpr std::uint16_t kTscyc = 100;

// The master's cycle n (0, 1, ...) starts at the first MCLK edge at or after the REGMODE
// write and then every TSCYC ticks (docs/timing.md, master timer); with TCYCSTART = 0 the
// MST begins on the first bit edge after that.
struct MasterClock {
  Time first;
  Timing t;
  Time cycle_start(int n) const {
    return first + static_cast<Time>(n) * kTscyc * t.tick_edges() * t.mclk();
  }
  Time mst_start(int n) const { return on_bit_grid(cycle_start(n), t); }
};

MasterClock start(Ring& ring, const Timing& t) {
  ring.run_for(1'234'567);  // anywhere off the grids
  const Time now = ring.scheduler.now();
  start_master(ring.chip(0));
  return MasterClock{ceil_to(now, t.mclk()), t};
}

TEST(TelegramMaster, SendsOneMstPerCycleWithPhas0EvenWithEntmtOff) {
  // Delta spec 2.6.2: ENTMT suppresses ATs and MDTs; "the SERCON816 transmits MST's of
  // phase 0" after the watchdog: MSTs do not depend on ENTMT. Facts §2: MST = address 255
  // plus one data byte, the phase.
  Ring ring(1, kFibre);
  const Timing t = timing_16mbit();
  program_master(ring.chip(0), t, kTscyc, 2);
  const MasterClock clock = start(ring, t);
  ring.run_for(350 * sim::kMicrosecond);
  const auto& seen = ring.fibre_from(0).seen;
  ASSERT_EQ(seen.size(), 4u);
  for (std::size_t n = 0; n < 4; ++n) {
    EXPECT_EQ(seen[n].start, clock.mst_start(static_cast<int>(n))) << "cycle " << n;
    EXPECT_EQ(seen[n].address, 0xFF);
    EXPECT_EQ(seen[n].data, std::vector<std::uint8_t>{2});
    EXPECT_TRUE(seen[n].ok);
  }
  EXPECT_TRUE(ring.chip(0).reg_read(kIntStat) & kIntCycst);
}

TEST(TelegramMaster, TcycdelIsTheCounterWhenTheOwnMstComesBack) {
  // Facts §5: TCYCDEL is "a measured delay" the driver reads; documented decision: the
  // counter of the master's cycle at the returned MST's detection.
  Ring ring(1, kFibre);
  const Timing t = timing_16mbit();
  program_master(ring.chip(0), t, kTscyc, 0);
  const MasterClock clock = start(ring, t);
  ring.run_for(50 * sim::kMicrosecond);
  const std::array<std::uint8_t, 1> phase0{0};
  const Time back = clock.mst_start(0) + kFibre;
  const Time detected = detection(back + static_cast<Time>(line_bits(0xFF, phase0)) * t.bit, t);
  const std::uint16_t expected = counter_at(detected, clock.cycle_start(0), t);
  EXPECT_EQ(ring.chip(0).reg_read(kTcycdel), expected);
  EXPECT_GT(expected, t.tcntst);
}

TEST(TelegramMaster, TcycdelIsMeasuredEvenWhenTheReturnComesAfterTheWindow) {
  // Documented decision (telegram-processing.md, "TCYCDEL"): the counter when the own MST
  // comes back, whether inside JTRDEL1..JTRDEL2 or not; a late one counts once in NMSTERR
  // (when the window closes), not again when it comes. A driver whose ring delay grew past
  // JTRDEL2 reads the new delay here.
  Ring ring(1, kFibre);
  const Timing t = timing_16mbit();
  program_master(ring.chip(0), t, kTscyc, 0);
  const std::array<std::uint8_t, 1> phase0{0};
  ring.chip(0).reg_write(kJtrdel1, 1);
  const MasterClock clock = start(ring, t);
  const Time back = clock.mst_start(0) + kFibre;
  const Time detected = detection(back + static_cast<Time>(line_bits(0xFF, phase0)) * t.bit, t);
  const std::uint16_t expected = counter_at(detected, clock.cycle_start(0), t);
  ASSERT_GT(expected - 1, t.tcntst);  // the window closes after the MST went out
  ring.chip(0).reg_write(kJtrdel2, expected - 1);
  ring.run_for(350 * sim::kMicrosecond);  // 4 MSTs, each back one step after its window
  EXPECT_EQ(ring.chip(0).reg_read(kTcycdel), expected);
  EXPECT_TRUE(ring.chip(0).reg_read(kIntStat) & kIntRetmst);
  EXPECT_EQ(ring.chip(0).ram_read(10), 4);
}

TEST(TelegramMaster, ReturnInsideJtrdelWindowIsNoError) {
  Ring ring(1, kFibre);
  const Timing t = timing_16mbit();
  program_master(ring.chip(0), t, kTscyc, 0);
  ring.chip(0).reg_write(kJtrdel1, 1);
  ring.chip(0).reg_write(kJtrdel2, 60);
  start(ring, t);
  ring.run_for(1000 * sim::kMicrosecond);
  EXPECT_FALSE(ring.chip(0).reg_read(kIntStat) & kIntRetmst);
  EXPECT_EQ(ring.chip(0).ram_read(10), 0);
}

TEST(TelegramMaster, ReturnOutsideJtrdelWindowRaisesRetmstAndCountsNmsterr) {
  // Register table INT_RETMST: "own MST came back outside JTRDEL1..JTRDEL2"; datasheet
  // 4.2: RAM word 10 NMSTERR, error counter MST.
  Ring ring(1, kFibre);
  const Timing t = timing_16mbit();
  program_master(ring.chip(0), t, kTscyc, 0);
  ring.chip(0).reg_write(kJtrdel1, 1);
  ring.chip(0).reg_write(kJtrdel2, 3);  // the MST alone lasts longer than 3 µs
  start(ring, t);
  ring.run_for(350 * sim::kMicrosecond);  // 4 MSTs sent, 4 back, all late
  EXPECT_TRUE(ring.chip(0).reg_read(kIntStat) & kIntRetmst);
  EXPECT_EQ(ring.chip(0).ram_read(10), 4);
}

TEST(TelegramMaster, MissingReturnRaisesRetmstOncePerMst) {
  // Register table INT_RETMST: "... or not at all". Without a window (JTRDEL2 = 0) an MST
  // counts as missing when the next one goes out.
  Ring ring(1, kFibre);
  ring.fibre_from(0).cut();
  const Timing t = timing_16mbit();
  program_master(ring.chip(0), t, kTscyc, 0);
  start(ring, t);
  ring.run_for(350 * sim::kMicrosecond);  // MSTs of cycles 0..3; 0..2 judged missing
  EXPECT_TRUE(ring.chip(0).reg_read(kIntStat) & kIntRetmst);
  EXPECT_EQ(ring.chip(0).ram_read(10), 3);
}

// sercon.h: "a pin callback may read and write registers, RAM and pins". An INT0 handler
// for INT_RETMST finds NMSTERR already counting the MST it announces.
TEST(TelegramMaster, Int0CallbackOnRetmstReadsTheCountedError) {
  Ring ring(1, kFibre);
  ring.fibre_from(0).cut();
  const Timing t = timing_16mbit();
  program_master(ring.chip(0), t, kTscyc, 0);
  Chip& chip = ring.chip(0);
  chip.reg_write(kIen0A, kIntRetmst);
  std::vector<std::uint16_t> seen;
  chip.pin(Pin::INT0).watch([&chip, &seen](sim::Level level) {
    if (level != sim::Level::High) return;
    seen.push_back(chip.ram_read(10));
    chip.reg_write(kIntStat, kIntRetmst);  // acknowledge
  });
  start(ring, t);
  ring.run_for(350 * sim::kMicrosecond);  // MSTs of cycles 0..3; 0..2 judged missing
  EXPECT_EQ(seen, (std::vector<std::uint16_t>{1, 2, 3}));
}

TEST(TelegramMaster, MissingReturnIsJudgedWhenTheWindowEnds) {
  Ring ring(1, kFibre);
  ring.fibre_from(0).cut();
  const Timing t = timing_16mbit();
  program_master(ring.chip(0), t, kTscyc, 0);
  ring.chip(0).reg_write(kJtrdel1, 1);
  ring.chip(0).reg_write(kJtrdel2, 40);
  const MasterClock clock = start(ring, t);
  // The step out of JTRDEL2 = 40 in cycle 0: MCLKST + (40 - TCNTST) ticks after the start.
  const Time window_end =
      clock.cycle_start(0) + (t.mclkst + (40 - t.tcntst) * t.tick_edges()) * t.mclk();
  ring.scheduler.run_until(window_end - 1);
  EXPECT_FALSE(ring.chip(0).reg_read(kIntStat) & kIntRetmst);
  ring.scheduler.run_until(window_end);
  EXPECT_TRUE(ring.chip(0).reg_read(kIntStat) & kIntRetmst);
  EXPECT_EQ(ring.chip(0).ram_read(10), 1);
}

TEST(TelegramMaster, WatchdogStopsMdtsButMstsGoOnWithPhaseZero) {
  // Delta spec 2.6.2: INT_WDOG clears ENTMT ("transmission of ... MDT's (Master) will be
  // suppressed") and PHAS0 ("transmits MST's of phase 0").
  Ring ring(1, kFibre);
  Chip& m = ring.chip(0);
  const Timing t = timing_16mbit();
  program_master(m, t, kTscyc, 3);
  m.ram_write(0, 0x0046);  // COMPT0 (phase 0 after the watchdog): just the end marker
  m.ram_write(1, 0x0040);  // COMPT1
  transmit_header(m, 0x0040, 0x50FF, 50, 1, 0x0046);
  words(m, 0x0044, {0x8001, 0xBEEF});
  end_marker(m, 0x0046, 80);
  enable_transmission(m);
  m.reg_write(kTwdog, 250);  // expires 250 µs after it starts
  m.reg_write(kWdCtrl, 0x0001);
  start(ring, t);
  ring.run_for(600 * sim::kMicrosecond);
  const auto& seen = ring.fibre_from(0).seen;
  bool mdt_after_expiry = false;
  int msts_after = 0;
  bool expired = false;
  for (const Seen& s : seen) {
    const bool mst = s.data.size() == 1;
    if (mst && !s.data.empty() && s.data[0] == 0) {
      expired = true;
      ++msts_after;
    }
    if (expired && !mst) mdt_after_expiry = true;
  }
  EXPECT_TRUE(expired);
  EXPECT_GE(msts_after, 2);
  EXPECT_FALSE(mdt_after_expiry);
  EXPECT_FALSE(m.reg_read(kTpCtrl) & kEntmt);
  // Before the expiry, each cycle had its MST (phase 3) and its MDT.
  ASSERT_GE(seen.size(), 4u);
  EXPECT_EQ(seen[0].data, std::vector<std::uint8_t>{3});
  EXPECT_EQ(seen[1].address, 0xFF);
  EXPECT_EQ(seen[1].data, (std::vector<std::uint8_t>{0xEF, 0xBE}));
}

}  // namespace
}  // namespace sercon::chip

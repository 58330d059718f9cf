// A master and two slaves in a ring exchanging CP4 traffic, and the same ring in CP3 and in
// CP0 (datasheet §1 "Telegram processing", 4.2; facts §2 cycle, phases, MDT records by
// position, ATs at T1; facts §5 counter rules; docs/telegram-processing.md). Every
// telegram's start on every fibre is computed here from the headers, the fibre delays, the
// documented receiver/repeater delays and the counter rules, and compared to the
// picosecond; the data written into one chip's DPRAM must arrive in the others'.
#include <gtest/gtest.h>

#include <array>
#include <optional>

#include "telegram_bench.hpp"

namespace sercon::chip {
namespace {

using namespace telegram_testing;

constexpr Time kFibre = 1'000'000;
constexpr std::uint16_t kTscyc = 200;
constexpr std::uint16_t kT1[3] = {0, 20, 40};  // AT times of slaves 1 and 2
constexpr std::uint16_t kT2 = 80;              // MDT time in the master's cycle
constexpr std::uint16_t kMasterEnd = 150;
constexpr std::uint16_t kSlaveEnd = 120;
constexpr std::uint16_t kList = 0x020;

// Everything one cycle puts on the fibres, from the rules alone.
struct Expected {
  Time mst = 0, mdt = 0;  // at the master's TxD
  Time load[3] = {};      // slave counter loads
  Time at[3] = {};        // slave k's AT at its TxD
  Time mst_rep[3] = {};   // slave k repeats the MST at its TxD
  Time mdt_rep[3] = {};   // slave k repeats the MDT
  Time at1_rep2 = 0;      // slave 2 repeats slave 1's AT
  Time at_back[3] = {};   // AT k at the master's RxD
  Time mdt_in[3] = {};    // MDT at slave k's RxD
};

Expected expect(Time cycle_start, const Timing& t, std::uint8_t mst_phase) {
  Expected e;
  const std::array<std::uint8_t, 1> phase{mst_phase};
  const Time mst_len = static_cast<Time>(line_bits(0xFF, phase)) * t.bit;
  e.mst = on_bit_grid(cycle_start, t);
  Time mst_in = e.mst + kFibre;
  for (int k = 1; k <= 2; ++k) {
    e.load[k] = detection(mst_in + mst_len, t);  // the counter loads at the MST's detection
    e.mst_rep[k] = repeated(mst_in, t);
    e.at[k] = on_bit_grid(cycle_time(e.load[k], kT1[k], t), t);
    mst_in = e.mst_rep[k] + kFibre;
  }
  e.at1_rep2 = repeated(e.at[1] + kFibre, t);
  e.at_back[1] = e.at1_rep2 + kFibre;
  e.at_back[2] = e.at[2] + kFibre;
  e.mdt = on_bit_grid(cycle_time(cycle_start, kT2, t), t);
  e.mdt_in[1] = e.mdt + kFibre;
  e.mdt_rep[1] = repeated(e.mdt_in[1], t);
  e.mdt_in[2] = e.mdt_rep[1] + kFibre;
  e.mdt_rep[2] = repeated(e.mdt_in[2], t);
  return e;
}

std::vector<Time> starts(const TestFibre& f) {
  std::vector<Time> v;
  for (const Seen& s : f.seen) v.push_back(s.start);
  return v;
}

// The ring in one communication phase: the list below sits where the phase takes it
// (datasheet 4.2: COMPT0 for phases 0..2, COMPT1 for 3..7), the other pointer names a list
// of nothing but an end marker; the phase's cycle time register (docs/timing.md, "Cycle
// time TSCYC": TSCYC0 in phases 0..2, TSCYC1 in 3..7) holds kTscyc, the other
// `other_tscyc`. The master's ENTMT is on from CP1 (facts §5: a driver sets it right after
// selecting CP1), the slaves' always.
class RingInPhase : public ::testing::Test {
 protected:
  RingInPhase(std::uint8_t phase, std::uint16_t other_tscyc)
      : ring(3, kFibre), phase_(phase), other_tscyc_(other_tscyc) {}

  void SetUp() override {
    t = timing_16mbit();
    // Where the first cycle will start: the MCLK edge after the REGMODE write below.
    ring.run_for(3'333'333);
    first = ceil_to(ring.scheduler.now(), t.mclk());
    e = expect(first, t, phase_);
    for (int k = 1; k <= 2; ++k) program_slave_list(k);
    program_master_list();
    start_master(ring.chip(0));
  }

  // The two list pointers (COMPT0, COMPT1) and the two cycle times (TSCYC0, TSCYC1).
  void point_lists(Chip& c, std::uint16_t list, std::uint16_t only_end) {
    const bool low = phase_ <= 2;
    c.ram_write(0, low ? list : only_end);
    c.ram_write(1, low ? only_end : list);
    c.reg_write(kTscyc0, low ? kTscyc : other_tscyc_);
    c.reg_write(kTscyc1, low ? other_tscyc_ : kTscyc);
  }

  // Slave k: its AT at T1, the MDT's record at POS 2(k-1), an end marker.
  void program_slave_list(int k) {
    Chip& s = ring.chip(static_cast<std::size_t>(k));
    program_slave(s, t, kTscyc);
    const auto adr = static_cast<std::uint16_t>(k);
    point_lists(s, kList, 0x0030);  // the other list: nothing but the end marker
    transmit_header(s, kList, static_cast<std::uint16_t>(0x5000 | adr), kT1[k], 2, 0x0027);
    words(s, 0x0024,
          {0x8002, static_cast<std::uint16_t>(0xA100 | adr),
           static_cast<std::uint16_t>(0xB200 | adr)});
    const std::uint16_t mdt_time = counter_at(e.mdt_in[k], e.load[k], t) - 1;
    receive_header(s, 0x0027, 0x18FF, mdt_time, 4, 0x0030);
    words(s, 0x002C, {0x8002, static_cast<std::uint16_t>(2 * (k - 1)), 0, 0});
    end_marker(s, 0x0030, kSlaveEnd);
    enable_transmission(s);
  }

  // Master: receive headers for both ATs (ACHK + TCHK), the MDT with two records, an end
  // marker.
  void program_master_list() {
    Chip& m = ring.chip(0);
    program_master(m, t, kTscyc, phase_);
    point_lists(m, kList, 0x0040);
    for (int k = 1; k <= 2; ++k) {
      const auto at = static_cast<std::uint16_t>(kList + 9 * (k - 1));
      const std::uint16_t time = counter_at(e.at_back[k], first, t) - 1;
      receive_header(m, at, static_cast<std::uint16_t>(0x1800 | k), time, 2,
                     static_cast<std::uint16_t>(at + 9));
      words(m, at + 5, {0x8002, 0, 0, 0});
    }
    transmit_header(m, 0x0032, 0x50FF, kT2, 4, 0x003E);
    words(m, 0x0036, {0x0002, 0x1111, 0x2222, 0x8002, 0x3333, 0x4444});
    end_marker(m, 0x003E, kMasterEnd);
    end_marker(m, 0x0040, kMasterEnd);
    if (phase_ >= 1) enable_transmission(m);
  }

  Time cycle(int n) const { return static_cast<Time>(n) * kTscyc * sim::kMicrosecond; }

  // What fibres 0, 1 and 2 carry in the first `cycles` cycles, from the rules alone: the
  // master's timer repeats its cycle every TSCYC µs exactly (docs/timing.md, "Master with
  // the internal timer"), and each slave follows the MST, so cycle n is cycle 0 moved by
  // n * TSCYC, to the picosecond. In CP0 the MSTs alone (facts §2: "CP0 MSTs only"): the
  // master's ENTMT is off, and the slaves' ATs wait for an MDT that asks for them
  // (docs/telegram-processing.md §6, FLMDTADR in phases 0..2).
  std::array<std::vector<Time>, 3> expected_starts(int cycles) const {
    std::array<std::vector<Time>, 3> f;
    for (int n = 0; n < cycles; ++n) {
      const Time c = cycle(n);
      if (phase_ == 0) {
        f[0].push_back(e.mst + c);
        f[1].push_back(e.mst_rep[1] + c);
        f[2].push_back(e.mst_rep[2] + c);
        continue;
      }
      f[0].insert(f[0].end(), {e.mst + c, e.mdt + c});
      f[1].insert(f[1].end(), {e.mst_rep[1] + c, e.at[1] + c, e.mdt_rep[1] + c});
      f[2].insert(f[2].end(), {e.mst_rep[2] + c, e.at1_rep2 + c, e.at[2] + c, e.mdt_rep[2] + c});
    }
    return f;
  }

  // Runs `cycles` cycles; every telegram on fibres 0, 1 and 2 starts where expected_starts
  // says.
  void run_and_expect_every_start(int cycles) {
    ring.run_for(cycles * kTscyc * sim::kMicrosecond);
    const auto expected = expected_starts(cycles);
    for (std::size_t i = 0; i < 3; ++i) {
      EXPECT_EQ(starts(ring.fibre_from(i)), expected[i]) << "fibre " << i;
    }
  }

  // Every MST came back to the master (NMSTERR, datasheet 4.2 RAM word 10) and came to each
  // slave in its JTSCYC window (docs/timing.md §4): no NMSTERR, no window flag.
  void expect_every_mst_on_time() {
    EXPECT_EQ(ring.chip(0).ram_read(10), 0);
    for (std::size_t k = 1; k <= 2; ++k) {
      EXPECT_EQ(ring.chip(k).ram_read(10), 0) << k;
      EXPECT_EQ(ring.chip(k).reg_read(kIntStat) & kWindowFlags, 0) << k;
    }
  }

  Ring ring;
  Timing t;
  Time first = 0;
  Expected e;

 private:
  std::uint8_t phase_;
  std::uint16_t other_tscyc_;
};

class Cp4Ring : public RingInPhase {
 protected:
  Cp4Ring() : RingInPhase(4, kTscyc) {}
};

// For thousands of cycles (issue 4's test clause; expected_starts says why cycle n is
// cycle 0 moved by n * TSCYC).
constexpr int kLongRun = 2000;

TEST_F(Cp4Ring, EveryTelegramStartsWhereHeadersAndDelaysSay) {
  run_and_expect_every_start(kLongRun);
}

// CP3 (facts §2: "the configured timing and telegram layout become active"): the traffic
// of CP4 — MST, each slave's AT at T1 after the MST's end at it, the MDT at T2 — from the
// list COMPT1 names and with TSCYC1 as the cycle (datasheet 4.2 COMPT1 for phases 3..7;
// docs/timing.md, "Cycle time TSCYC"). Here COMPT0 names an empty list and TSCYC0 is 300
// µs, so a chip that took the CP0..2 settings would put other telegrams on the fibres.
class Cp3Ring : public RingInPhase {
 protected:
  Cp3Ring() : RingInPhase(3, 300) {}
};

TEST_F(Cp3Ring, EveryTelegramStartsWhereHeadersAndDelaysSay) {
  run_and_expect_every_start(kLongRun);
  // Facts §2: the MST carries the phase (3) in its data byte; the ATs carry their drive's
  // address, the MDT address 255.
  std::vector<std::uint8_t> addresses;
  for (const Seen& s : ring.fibre_from(2).seen) {
    if (s.address == 0xFF && s.data.size() == 1) {
      EXPECT_EQ(s.data[0], 3);
    }
    if (addresses.size() < 4) addresses.push_back(s.address);
  }
  EXPECT_EQ(addresses, (std::vector<std::uint8_t>{0xFF, 1, 2, 0xFF}));
  // Every MST in its window, TSCYC1 after the one before; the slaves took phase 3.
  expect_every_mst_on_time();
  for (std::size_t k = 1; k <= 2; ++k) {
    EXPECT_EQ(ring.chip(k).reg_read(kPhase) >> 8, 3) << k;  // PHASR
  }
}

// CP0 (facts §2: "CP0 MSTs only (ring check ...)"): the MST with phase 0 at every cycle
// start of TSCYC0 (docs/timing.md, "Cycle time TSCYC"; TSCYC1 is 300 µs here), repeated
// by each slave 2 bit times later (docs/serial-and-ring.md, "Repeater"); nothing else on
// any fibre, although the slaves' COMPT0 lists hold an AT to send every cycle (FLMDTADR
// gate in phases 0..2, docs/telegram-processing.md §6) and the master's an MDT (ENTMT off,
// delta spec 2.6.2, as a driver leaves it until CP1, facts §5).
class Cp0Ring : public RingInPhase {
 protected:
  Cp0Ring() : RingInPhase(0, 300) {}
};

TEST_F(Cp0Ring, OnlyMstsCircleEachWhereTheRulesPutIt) {
  run_and_expect_every_start(kLongRun);
  for (std::size_t i = 0; i < 3; ++i) {
    for (const Seen& s : ring.fibre_from(i).seen) {
      ASSERT_EQ(s.address, 0xFF) << "fibre " << i << " at " << s.start;
      ASSERT_EQ(s.data, std::vector<std::uint8_t>{0}) << "fibre " << i << " at " << s.start;
      ASSERT_TRUE(s.ok);
    }
  }
  // Facts §2: "A master treats the ring as closed once its own MSTs come back": every one
  // did; each slave had its MST in its window.
  expect_every_mst_on_time();
  for (std::size_t k = 1; k <= 2; ++k) {
    EXPECT_FALSE(ring.chip(k).reg_read(kSlvFlags) & kFlmdtadr) << k;
  }
}

// Datasheet 4.2.1 ("TRT: time for the start of telegram in µs after end of MST") with the
// driver's TCNTST / MCLKST of facts §5, whose t_start (5.5 bit + 3.5 MCLK) is the whole
// delay from the MST's end to the counter load: at 16 Mbit/s and 32 MHz (the design case of
// docs/timing.md, "Deriving the driver formulas") a slave's AT at T1 begins on the first
// bit edge at or after the first MCLK edge at or after (end of the MST at its RxD) + T1 µs.
// Taken from what the fibres carried, not from the expectations above: the counter must not
// wait for a second synchroniser after the detection.
TEST_F(Cp4Ring, ASlavesAtBeginsT1MicrosecondsAfterTheMstEndedAtIt) {
  ring.run_for(kTscyc * sim::kMicrosecond);
  const std::array<std::uint8_t, 1> phase{4};
  const Time mst_len = static_cast<Time>(line_bits(0xFF, phase)) * t.bit;
  for (int k = 1; k <= 2; ++k) {
    const auto& into = ring.fibre_from(static_cast<std::size_t>(k - 1)).seen;
    const auto& out = ring.fibre_from(static_cast<std::size_t>(k)).seen;
    ASSERT_FALSE(into.empty());
    ASSERT_EQ(into.front().address, 0xFF);
    const Time mst_end = into.front().start + kFibre + mst_len;  // at slave k's RxD
    const Time at_t1 = mst_end + static_cast<Time>(kT1[k]) * sim::kMicrosecond;
    const Time expected = ceil_to(ceil_to(at_t1, t.mclk()), t.bit);
    bool found = false;
    for (const Seen& s : out) {
      if (s.address != k) continue;
      EXPECT_EQ(s.start, expected) << "slave " << k;
      found = true;
      break;
    }
    EXPECT_TRUE(found) << "slave " << k << " sent no AT";
  }
}

TEST_F(Cp4Ring, TelegramsCarryTheirAddressesAndData) {
  ring.run_for(kTscyc * sim::kMicrosecond);
  const auto& m = ring.fibre_from(0).seen;
  ASSERT_EQ(m.size(), 2u);
  EXPECT_EQ(m[1].address, 0xFF);  // facts §2: the CP3/4 MDT goes to address 255
  EXPECT_EQ(m[1].data, (std::vector<std::uint8_t>{0x11, 0x11, 0x22, 0x22, 0x33, 0x33, 0x44, 0x44}));
  const auto& s2 = ring.fibre_from(2).seen;
  ASSERT_EQ(s2.size(), 4u);
  EXPECT_EQ(s2[1].address, 1);
  EXPECT_EQ(s2[1].data, (std::vector<std::uint8_t>{0x01, 0xA1, 0x01, 0xB2}));
  EXPECT_EQ(s2[2].address, 2);
  EXPECT_EQ(s2[2].data, (std::vector<std::uint8_t>{0x02, 0xA1, 0x02, 0xB2}));
}

TEST_F(Cp4Ring, DataWrittenInOneDpramArrivesInTheOthers) {
  ring.run_for(2 * kTscyc * sim::kMicrosecond);
  // Datasheet 4.2.2 POS: each slave takes its record from the MDT.
  EXPECT_EQ(ring.chip(1).ram_read(0x002E), 0x1111);
  EXPECT_EQ(ring.chip(1).ram_read(0x002F), 0x2222);
  EXPECT_EQ(ring.chip(2).ram_read(0x002E), 0x3333);
  EXPECT_EQ(ring.chip(2).ram_read(0x002F), 0x4444);
  // The master stores each AT in its receive container.
  EXPECT_EQ(ring.chip(0).ram_read(kList + 7), 0xA101);
  EXPECT_EQ(ring.chip(0).ram_read(kList + 8), 0xB201);
  EXPECT_EQ(ring.chip(0).ram_read(kList + 9 + 7), 0xA102);
  EXPECT_EQ(ring.chip(0).ram_read(kList + 9 + 8), 0xB202);
  // A new value written by the host goes out in the next cycle.
  ring.chip(0).ram_write(0x0037, 0x5A5A);
  ring.chip(2).ram_write(0x0025, 0x0F0F);
  ring.run_for(kTscyc * sim::kMicrosecond);
  EXPECT_EQ(ring.chip(1).ram_read(0x002E), 0x5A5A);
  EXPECT_EQ(ring.chip(0).ram_read(kList + 9 + 7), 0x0F0F);
}

TEST_F(Cp4Ring, ReceiveHeadersReportGoodTelegrams) {
  // Datasheet 4.2.1: VAL = 1 (single buffer, data valid), RERR = 0, NERR stays 0.
  ring.run_for(2 * kTscyc * sim::kMicrosecond);
  for (int k = 1; k <= 2; ++k) {
    const auto at = static_cast<std::uint16_t>(kList + 9 * (k - 1));
    EXPECT_EQ(ring.chip(0).ram_read(at), 0x1800 | 0x0400 | k) << "AT " << k;
    EXPECT_EQ(ring.chip(0).ram_read(at + 4), 0) << "NERR " << k;
    EXPECT_EQ(ring.chip(static_cast<std::size_t>(k)).ram_read(0x0027), 0x18FF | 0x0400);
  }
}

TEST_F(Cp4Ring, TelegramInterruptsAreLatched) {
  // Register table 0x04: INT_CYCST, INT_REND, INT_TEND, INT_ENDMK; no INT_RERR.
  ring.run_for(kTscyc * sim::kMicrosecond);
  for (std::size_t i = 0; i < 3; ++i) {
    const std::uint16_t s = ring.chip(i).reg_read(kIntStat);
    EXPECT_TRUE(s & kIntCycst) << i;
    EXPECT_TRUE(s & kIntRend) << i;
    EXPECT_TRUE(s & kIntTend) << i;
    EXPECT_TRUE(s & kIntEndmk) << i;
    EXPECT_FALSE(s & kIntRerr) << i;
  }
}

// Register table 0x04 (INTSTAT) INT_REND and 0x28 INT_RSCEND: latched at every accepted
// receive telegram until the host clears them (docs/telegram-processing.md, interrupts).
// The processor keeps whether they are latched (a raise then changes nothing): cleared by
// the host, each is latched again by the next telegram received.
TEST_F(Cp4Ring, RendAndRscendClearedComeAgainWithTheNextTelegram) {
  ring.run_for(kTscyc * sim::kMicrosecond);
  for (std::size_t i = 0; i < 3; ++i) {
    ASSERT_TRUE(ring.chip(i).reg_read(kIntStat) & kIntRend) << i;
    ASSERT_TRUE(ring.chip(i).reg_read(kWdCtrl) & kIntRscend) << i;
    ring.chip(i).reg_write(kIntStat, kIntRend);
    ring.chip(i).reg_write(kWdCtrl, ring.chip(i).reg_read(kWdCtrl));  // CLR_RSCEND, RW bits kept
    EXPECT_FALSE(ring.chip(i).reg_read(kIntStat) & kIntRend) << i;
    EXPECT_FALSE(ring.chip(i).reg_read(kWdCtrl) & kIntRscend) << i;
  }
  ring.run_for(kTscyc * sim::kMicrosecond);
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_TRUE(ring.chip(i).reg_read(kIntStat) & kIntRend) << i;
    EXPECT_TRUE(ring.chip(i).reg_read(kWdCtrl) & kIntRscend) << i;
  }
}

TEST_F(Cp4Ring, TendAndEndmkComeAtTheirTimes) {
  // INT_TEND at the end of the own telegram on the line; INT_ENDMK at the step out of
  // TEND (datasheet 4.2.3). In a master that time counts from its own cycle start, not from
  // the end of its MST (docs/telegram-processing.md §3, "Master — counter reference").
  const std::array<std::uint8_t, 8> data{0x11, 0x11, 0x22, 0x22, 0x33, 0x33, 0x44, 0x44};
  const Time end = e.mdt + static_cast<Time>(line_bits(0xFF, data)) * t.bit;
  ring.scheduler.run_until(end - 1);
  ring.chip(0).reg_write(kIntStat, 0xFFFF);
  EXPECT_FALSE(ring.chip(0).reg_read(kIntStat) & kIntTend);
  ring.scheduler.run_until(end);
  EXPECT_TRUE(ring.chip(0).reg_read(kIntStat) & kIntTend);
  const Time endmk = cycle_time(first, kMasterEnd, t);
  ring.scheduler.run_until(endmk - 1);
  EXPECT_FALSE(ring.chip(0).reg_read(kIntStat) & kIntEndmk);
  ring.scheduler.run_until(endmk);
  EXPECT_TRUE(ring.chip(0).reg_read(kIntStat) & kIntEndmk);
}

// INT_TEND latched when a telegram starts and cleared by the host before its end (the
// processor holds that event out of the scheduler's queue while the flag is latched): it
// is latched again at the telegram's end, not before; cleared at that very instant after
// the end ran, it stays clear.
TEST_F(Cp4Ring, TendClearedDuringATelegramComesAtItsEnd) {
  const std::array<std::uint8_t, 8> data{0x11, 0x11, 0x22, 0x22, 0x33, 0x33, 0x44, 0x44};
  const Time cycle = kTscyc * sim::kMicrosecond;
  const Time end = e.mdt + cycle + static_cast<Time>(line_bits(0xFF, data)) * t.bit;
  ring.scheduler.run_until(e.mdt + cycle + t.bit);
  ASSERT_TRUE(ring.chip(0).reg_read(kIntStat) & kIntTend);
  ring.chip(0).reg_write(kIntStat, kIntTend);
  ring.scheduler.run_until(end - 1);
  EXPECT_FALSE(ring.chip(0).reg_read(kIntStat) & kIntTend);
  ring.scheduler.run_until(end);
  EXPECT_TRUE(ring.chip(0).reg_read(kIntStat) & kIntTend);
  ring.chip(0).reg_write(kIntStat, kIntTend);
  ring.scheduler.run_until(end + 2 * t.bit);
  EXPECT_FALSE(ring.chip(0).reg_read(kIntStat) & kIntTend);
}

// The same for INT_ENDMK: latched when the walk reaches the end marker, cleared by the host
// before the step out of TEND, latched again at that step.
TEST_F(Cp4Ring, EndmkClearedBeforeTheEndMarkerComesAtItsTime) {
  const Time endmk = cycle_time(first, kMasterEnd, t) + kTscyc * sim::kMicrosecond;
  ring.scheduler.run_until(endmk - 1);
  ASSERT_TRUE(ring.chip(0).reg_read(kIntStat) & kIntEndmk);
  ring.chip(0).reg_write(kIntStat, kIntEndmk);
  EXPECT_FALSE(ring.chip(0).reg_read(kIntStat) & kIntEndmk);
  ring.scheduler.run_until(endmk);
  EXPECT_TRUE(ring.chip(0).reg_read(kIntStat) & kIntEndmk);
}

// A second CP4 ring set up as the test's own: the twin whose end marker takes the ordinary
// path (armed while INT_ENDMK is clear), to compare a held one with.
class Cp4Twin : public Cp4Ring {
 public:
  Cp4Twin() { SetUp(); }
  using Cp4Ring::first;
  using Cp4Ring::ring;
  using Cp4Ring::t;
  void TestBody() override {}
};

// Steps the ring's events one by one until the master's INT_ENDMK is latched; its time, or
// -1 if it is not latched by `limit`.
Time step_until_endmk(Ring& ring, Time limit) {
  while (!(ring.chip(0).reg_read(kIntStat) & kIntEndmk)) {
    const std::optional<Time> next = ring.scheduler.next_time();
    if (!next || *next > limit) return -1;
    ring.scheduler.step();
  }
  return ring.scheduler.now();
}

// INT_ENDMK at the step out of TEND (datasheet 4.2.3) counts on the tick of the time base,
// which MCLKDIV makes; a new MCLKDIV counts from the tick after the pending one (docs/timing.md,
// "Cycle-time events": moved if MCLKDIV changes). Cycle 1's end marker with MCLKDIV written
// at `y`, before its step: on the twin's ordinary path INT_ENDMK is cleared in cycle 0 after
// its marker, so cycle 1's walk arms the marker; held, INT_ENDMK is latched since cycle 0
// when the walk reads it and cleared right after the MCLKDIV write. The time INT_ENDMK latches, by
// steps.
Time endmk_after_mclkdiv_change(bool held, Time y) {
  Cp4Twin r;
  Chip& m = r.ring.chip(0);
  const Time marker = cycle_time(r.first, kMasterEnd, r.t);
  const Time cycle = kTscyc * sim::kMicrosecond;
  if (!held) {
    r.ring.scheduler.run_until(marker + 10 * sim::kMicrosecond);
    EXPECT_TRUE(m.reg_read(kIntStat) & kIntEndmk);
    m.reg_write(kIntStat, kIntEndmk);
  }
  r.ring.scheduler.run_until(y);
  EXPECT_EQ(static_cast<bool>(m.reg_read(kIntStat) & kIntEndmk), held);
  m.reg_write(kClockDiv, static_cast<std::uint16_t>(r.t.mclkst << 8 | (r.t.mclkdiv - 1) / 2));
  if (held) {
    m.reg_write(kIntStat, kIntEndmk);
    EXPECT_FALSE(m.reg_read(kIntStat) & kIntEndmk);
  }
  return step_until_endmk(r.ring, marker + 2 * cycle);
}

// The held marker latches INT_ENDMK at the very time the twin's armed one does: with MCLKDIV
// written well before the step (the step moves), within the tick before it (the pending
// tick: it stays), and 1 ps before it (the change counts from the MCLK edge of the step).
TEST_F(Cp4Ring, EndmkHeldAcrossAnMclkdivChangeComesWhereAnArmedOneWould) {
  const Time marker = cycle_time(first, kMasterEnd, t) + cycle(1);  // MCLKDIV unchanged
  const Time tick = t.tick_edges() * t.mclk();
  // After the MDT, before the step; then in the tick before the step; then just before it.
  for (const Time y : {first + cycle(1) + 100 * sim::kMicrosecond, marker - tick / 2, marker - 1}) {
    const Time armed = endmk_after_mclkdiv_change(false, y);
    ASSERT_GT(armed, y);
    if (y < marker - tick) {
      EXPECT_NE(armed, marker) << "the MCLKDIV write moved the step";
    }
    EXPECT_EQ(endmk_after_mclkdiv_change(true, y), armed) << "MCLKDIV written at " << y;
  }
}

// INT_ENDMK latched all through cycle 1, so that cycle's end marker was held; cleared only
// after cycle 2 has started, before cycle 2's walk reads its marker. Cycle 1's held marker
// never runs (its step out of TEND belongs to a cycle that is over); cycle 2's latches
// INT_ENDMK at its own step (datasheet 4.2.3): one cycle after the time of
// EndmkClearedBeforeTheEndMarkerComesAtItsTime.
TEST_F(Cp4Ring, EndmkClearedInTheNextCycleComesOnlyAtThatCyclesMarker) {
  const Time endmk = cycle_time(first, kMasterEnd, t) + cycle(2);
  ring.scheduler.run_until(first + cycle(2) + 10 * sim::kMicrosecond);
  ASSERT_TRUE(ring.chip(0).reg_read(kIntStat) & kIntEndmk);
  ring.chip(0).reg_write(kIntStat, kIntEndmk);
  EXPECT_FALSE(ring.chip(0).reg_read(kIntStat) & kIntEndmk);
  ring.scheduler.run_until(endmk - 1);
  EXPECT_FALSE(ring.chip(0).reg_read(kIntStat) & kIntEndmk);
  ring.scheduler.run_until(endmk);
  EXPECT_TRUE(ring.chip(0).reg_read(kIntStat) & kIntEndmk);
}

TEST_F(Cp4Ring, SlavesCountCyclesWithoutMstInNmsterr) {
  // Datasheet 4.2: RAM word 10 NMSTERR, "error counter MST". Decision: a slave counts every
  // cycle it free-wheels because no MST came (docs/timing.md, substitute cycle).
  ring.run_for(2 * kTscyc * sim::kMicrosecond);
  EXPECT_EQ(ring.chip(1).ram_read(10), 0);
  ring.fibre_from(0).cut();
  ring.run_for(3 * kTscyc * sim::kMicrosecond);
  EXPECT_EQ(ring.chip(1).ram_read(10), 3);
  EXPECT_EQ(ring.chip(2).ram_read(10), 3);
  EXPECT_TRUE(ring.chip(1).reg_read(kIntStat) & kIntMstMiss);
}

TEST_F(Cp4Ring, MissingAtSetsRerrAtTheMaster) {
  // Slave 2 stops sending (ENTMT = 0): the master's header for its AT gets RERR and NERR.
  ring.run_for(kTscyc * sim::kMicrosecond);
  ring.chip(2).reg_write(kTpCtrl, 0);
  ring.run_for(2 * kTscyc * sim::kMicrosecond);
  const std::uint16_t at2 = kList + 9;
  EXPECT_EQ(ring.chip(0).ram_read(at2) & 0x2000, 0x2000);
  EXPECT_EQ(ring.chip(0).ram_read(at2 + 4), 2);
  EXPECT_EQ(ring.chip(0).ram_read(kList) & 0x2000, 0);  // slave 1 still fine
  EXPECT_TRUE(ring.chip(0).reg_read(kIntStat) & kIntRerr);
}

}  // namespace
}  // namespace sercon::chip

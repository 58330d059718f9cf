// Phases 1 and 2 at 2 Mbit/s with the real driver's master DPRAM layout of sercos-facts §5,
// word for word, and a slave answering through FLMDTADR (delta spec 2.9): the SERCON816
// answers each MDT with its address once; the SERCON410B keeps answering until an MDT with
// another address comes.
#include <gtest/gtest.h>

#include <array>

#include "telegram_bench.hpp"

namespace sercon::chip {
namespace {

using namespace telegram_testing;

constexpr Time kFibre = 1'000'000;
constexpr std::uint16_t kTscyc = 2000;  // facts §2: a real master used 2 ms in CP1 and CP2
constexpr std::uint16_t kMdtHeader = 0x014;

// The real driver's CP1/2 list (facts §5): receive header at 0x00B = 0x1000 (TCHK), time
// 100 µs, length 2, next 0x014, errors 0, container 0xC002, POS 0, status word 0x012,
// service info 0x013; transmit header at 0x014 = 0x5000 + drive address, time 600 µs,
// length 2, next 0x01B, container 0xC002, control word 0x0001, info 0; end marker at
// 0x01B = 0xC000, time 950 µs. Fixed words: COMPT0 0x000B, COMPT1 0x0020, SCPT0..7.
void facts_master_layout(Chip& m, std::uint16_t mdt_word0) {
  words(m, 0x000, {0x000B, 0x0020, 0x273, 0x2A5, 0x2D7, 0x309, 0x33B, 0x36D, 0x39F, 0x3D1, 0});
  words(m, 0x00B, {0x1000, 100, 2, 0x014, 0, 0xC002, 0, 0, 0});
  words(m, 0x014, {mdt_word0, 600, 2, 0x01B, 0xC002, 0x0001, 0});
  words(m, 0x01B, {0xC000, 950});
  words(m, 0x020, {0xC000, 950});  // CP3/4 list: not used here
}

class Cp12 : public ::testing::TestWithParam<Variant> {
 protected:
  Cp12() : ring(2, kFibre, config_for(GetParam())) {}

  static ChipConfig config_for(Variant v) {
    ChipConfig c;
    c.variant = v;
    c.sbaud16 = v == Variant::Sercon410B;  // the 410B runs with SREGEN tied high
    return c;
  }

  // Starts the ring with the master sending `mdt_word0` in its MDT header; the slave (drive
  // 1) answers at the time that puts its AT into the master's 100 µs window. Its MDT
  // receive header's word 0 is `slave_rx_word0` (default: ACHK, TCHK, address 1).
  void start(std::uint16_t mdt_word0, std::uint16_t slave_rx_word0 = 0x1801) {
    t = timing_2mbit();
    ring.run_for(7'777'777);
    first = ceil_to(ring.scheduler.now(), t.mclk());
    const std::array<std::uint8_t, 1> phase{1};
    const Time mst_in = on_bit_grid(first, t) + kFibre;
    // The slave's counter loads at its detection of the MST.
    load = detection(mst_in + static_cast<Time>(line_bits(0xFF, phase)) * t.bit, t);
    // T1: the slave time whose AT begins at the master while its counter reads 101, i.e.
    // 100 µs into the window (datasheet 4.2.1 TRT: "time for the start of telegram").
    for (std::uint16_t c = t.tcntst; c < 400; ++c) {
      if (counter_at(on_bit_grid(cycle_time(load, c, t), t) + kFibre, first, t) == 101) {
        t1 = c;
        break;
      }
    }
    ASSERT_NE(t1, 0);
    mdt_start = on_bit_grid(cycle_time(first, 600, t), t);
    const std::uint16_t mdt_time = counter_at(mdt_start + kFibre, load, t) - 1;

    Chip& s = ring.chip(1);
    program_slave(s, t, kTscyc);
    words(s, 0x000, {0x0100, 0x0100});
    transmit_header(s, 0x100, 0x5001, t1, 2, 0x107);
    words(s, 0x104, {0x8002, 0x0001, 0x0000});  // status bit 0: the drive is there
    receive_header(s, 0x107, slave_rx_word0, mdt_time, 2, 0x110);
    words(s, 0x10C, {0x8002, 0, 0, 0});
    end_marker(s, 0x110, 1000);
    enable_transmission(s);

    Chip& m = ring.chip(0);
    program_master(m, t, kTscyc, 1);
    facts_master_layout(m, mdt_word0);
    enable_transmission(m);
    start_master(m);
  }

  Time cycle(int n) const { return static_cast<Time>(n) * kTscyc * sim::kMicrosecond; }
  Time at_start(int n) const { return on_bit_grid(cycle_time(load, t1, t), t) + cycle(n); }
  // ATs the slave sent, by cycle number.
  std::vector<int> at_cycles() const {
    std::vector<int> v;
    for (const Seen& s : ring.fibres[1]->seen) {
      if (s.address != 1) continue;
      for (int n = 0; n < 10; ++n) {
        if (s.start == at_start(n)) v.push_back(n);
      }
    }
    return v;
  }
  void run_cycles(int n) { ring.run_for(n * kTscyc * sim::kMicrosecond); }
  // The drive's INTSTAT latched over cycles 1 and 2 (cleared after cycle 0).
  std::uint16_t intstat_of_cycles_1_and_2() {
    run_cycles(1);
    ring.chip(1).reg_write(kIntStat, 0xFFFF);
    run_cycles(2);
    return ring.chip(1).reg_read(kIntStat);
  }
  // Three cycles after one MDT (send once) to the drive: the 816 answers it once; the 410B's
  // flag stays, so its AT goes out in cycles 1 and 2 too (delta spec 2.9.2).
  void expect_one_mdt_answered_as_the_variant_does() {
    run_cycles(3);
    const bool is816 = GetParam() == Variant::Sercon816;
    const std::vector<int> expected = is816 ? std::vector<int>{1} : std::vector<int>{1, 2};
    EXPECT_EQ(at_cycles(), expected);
    EXPECT_EQ((ring.chip(1).reg_read(kSlvFlags) & kFlmdtadr) != 0, !is816) << "FLMDTADR";
  }

  Ring ring;
  Timing t;
  Time first = 0, load = 0, mdt_start = 0;
  std::uint16_t t1 = 0;
};

TEST_P(Cp12, FactsLayoutWorksUnchanged) {
  start(0x5001);  // facts §5: 0x5000 + address, send every cycle
  run_cycles(3);
  Chip& m = ring.chip(0);
  // The MDT at 600 µs of every cycle, to drive 1, control word 0x0001 and info 0.
  std::vector<Time> mdts;
  for (const Seen& s : ring.fibres[0]->seen) {
    if (s.data.size() == 4) {
      mdts.push_back(s.start);
      EXPECT_EQ(s.address, 1);
      EXPECT_EQ(s.data, (std::vector<std::uint8_t>{0x01, 0x00, 0x00, 0x00}));
    }
  }
  EXPECT_EQ(mdts, (std::vector<Time>{mdt_start, mdt_start + cycle(1), mdt_start + cycle(2)}));
  // The drive answers from the cycle after the first MDT (facts §2: present when its AT
  // comes back with status bit 0 set). Datasheet 4.2.1 ACHK = 0: "The received address is
  // stored at ADR"; VAL = 1, RERR = 0; NERR counts the one cycle without an AT.
  EXPECT_EQ(at_cycles(), (std::vector<int>{1, 2}));
  EXPECT_EQ(m.ram_read(0x00B), 0x1000 | 0x0400 | 0x0001);
  EXPECT_EQ(m.ram_read(0x00F), 1);
  EXPECT_EQ(m.ram_read(0x012), 0x0001);
  EXPECT_EQ(m.ram_read(0x013), 0x0000);
  // The slave took the MDT's words into its container.
  EXPECT_EQ(ring.chip(1).ram_read(0x10E), 0x0001);
  EXPECT_EQ(ring.chip(1).ram_read(0x107), 0x1801 | 0x0400);
}

TEST_P(Cp12, OneMdtBringsOneAtOnThe816AndAnswersUntilAnotherAddressOnThe410B) {
  // Delta spec 2.9.2: "In the SERCON816, the flag FLMDTADR is reset after starting to send
  // a telegram ... Therefore sending AT's can occur only once." SERCON410B: "reset only
  // after a new MDT is received including a different address ... A missing MDT does not
  // reset the flag causing AT's to be send multiple times."
  start(0x4801);  // send once (facts §5: 0x4800 + address)
  run_cycles(1);
  EXPECT_EQ(ring.chip(0).ram_read(kMdtHeader), 0x4001);  // EN written back as 0
  EXPECT_TRUE(ring.chip(1).reg_read(kSlvFlags) & kFlmdtadr);
  run_cycles(2);                               // cycles 1 and 2: no MDT at all
  ring.chip(0).ram_write(kMdtHeader, 0x5002);  // from cycle 3 on: MDTs to drive 2
  run_cycles(3);
  const bool is816 = GetParam() == Variant::Sercon816;
  const std::vector<int> expected = is816 ? std::vector<int>{1} : std::vector<int>{1, 2, 3};
  EXPECT_EQ(at_cycles(), expected);
  EXPECT_FALSE(ring.chip(1).reg_read(kSlvFlags) & kFlmdtadr);
}

TEST_P(Cp12, EntmtOffKeepsTheAtBackAndTheRequestPending) {
  // Delta spec 2.6.2: "By reset of ENTMT transmission of AT's (Slaves) ... will be
  // suppressed". The request (FLMDTADR) stays until an AT is actually started.
  start(0x4801);
  ring.chip(1).reg_write(kTpCtrl, 0);
  run_cycles(3);
  EXPECT_TRUE(at_cycles().empty());
  EXPECT_TRUE(ring.chip(1).reg_read(kSlvFlags) & kFlmdtadr);
  // The MSTs still pass the slave's repeater, and the master still gets them back.
  EXPECT_EQ(ring.chip(0).ram_read(10), 0);
  ring.chip(1).reg_write(kTpCtrl, kEntmt);
  run_cycles(1);
  EXPECT_EQ(at_cycles(), std::vector<int>{3});
}

// An ACHK = 1 header for address 255 (TCHK = 0) is offered the next cycle's MST and sets
// FLMDTADR before the MST is withdrawn at its detection (doc §3: "VAL is put back as it was
// and the header waits again"; the header waits as if it had not been offered). No MDT ever
// comes (the master's MDT header is idle), so the drive must not answer (delta spec 2.9:
// it sends only when requested by an MDT with its address).
TEST_P(Cp12, MstTakenByABroadcastHeaderDoesNotRequestAnAt) {
  start(0x4000, 0x08FF);  // master: MDT header idle; slave: ACHK, TCHK = 0, address 255
  run_cycles(3);
  EXPECT_TRUE(at_cycles().empty());
  EXPECT_FALSE(ring.chip(1).reg_read(kSlvFlags) & kFlmdtadr) << "FLMDTADR";
}

// Control: the slave's header for its own address; the MST is another address.
TEST_P(Cp12, NoMdtRequestsNoAt) {
  start(0x4000, 0x0801);
  run_cycles(3);
  EXPECT_TRUE(at_cycles().empty());
  EXPECT_FALSE(ring.chip(1).reg_read(kSlvFlags) & kFlmdtadr) << "FLMDTADR";
}

// Delta spec 2.9.2: "In the SERCON410B the flag (FLMDTADR) is reset only after a new MDT is
// received including a different address than the expected one. A missing MDT does not
// reset the flag causing AT's to be send multiple times." The drive's MDT header does not
// check the time (ACHK, TCHK = 0), so in the cycles without MDT it still waits when the
// next MST (address 255) comes: an MST is no MDT and must not clear the flag. The master
// sends one MDT (send once) in cycle 0 and none in cycles 1 and 2.
TEST_P(Cp12, UntimedMdtHeaderKeepsTheRequestUntilAnotherMdtAddress) {
  start(0x4801, 0x0801);  // slave: ACHK, TCHK = 0, address 1
  expect_one_mdt_answered_as_the_variant_does();
}

// Control: the same with the timed header (the MST is outside its window).
TEST_P(Cp12, TimedMdtHeaderKeepsTheRequestUntilAnotherMdtAddress) {
  start(0x4801, 0x1801);
  expect_one_mdt_answered_as_the_variant_does();
}

// Delta spec 2.9.1: in phases 1 and 2 "the drive ... should send a telegram only in case it
// is requested to do so by the master. After the request the telegram should be send only
// once"; 2.9.2: "In the SERCON816, the flag FLMDTADR is reset after starting to send a
// telegram when initiated when the flag is set". The MDT of cycle 0 requests an AT; the
// master then goes to CP3 for cycle 1, where the drive's AT (its one list serves COMPT0 and
// COMPT1) goes out ungated while the flag is set, and back to CP1 for cycle 2 with no MDT.
// On the 816 the CP3 AT started with the flag set and reset it: no second AT in cycle 2 for
// the one request. The 410B keeps the flag until an MDT with another address (its bug).
TEST_P(Cp12, AnAtStartedInCp3ResetsTheRequestOnThe816) {
  start(0x4801);  // send once: one MDT, in cycle 0
  ring.scheduler.run_until(first + 1000 * sim::kMicrosecond);
  ring.chip(0).reg_write(kPhase, 3);  // cycle 1 in CP3 (the master's CP3 list: end marker)
  ring.scheduler.run_until(first + cycle(1) + 1000 * sim::kMicrosecond);
  ring.chip(0).reg_write(kPhase, 1);  // cycle 2 back in CP1
  ring.scheduler.run_until(first + cycle(3) - 100 * sim::kMicrosecond);
  ASSERT_EQ(ring.chip(1).reg_read(kPhase) >> 8, 1);  // PHASR: the drive is in CP1 again
  // The cycles in which the drive's AT left it: address 1 near T1, not the MDT it repeats
  // at 600 µs (the MST of phase 3 is a stuffed bit longer than that of phase 1, so the CP3
  // AT is not at at_start(1)).
  std::vector<int> ats;
  for (const Seen& x : ring.fibres[1]->seen) {
    const Time in_cycle = (x.start - first) % cycle(1);
    if (x.address == 1 && in_cycle < at_start(0) - first + 5 * t.bit) {
      ats.push_back(static_cast<int>((x.start - first) / cycle(1)));
    }
  }
  const bool is816 = GetParam() == Variant::Sercon816;
  const std::vector<int> expected = is816 ? std::vector<int>{1} : std::vector<int>{1, 2};
  EXPECT_EQ(ats, expected);
  EXPECT_EQ((ring.chip(1).reg_read(kSlvFlags) & kFlmdtadr) != 0, !is816) << "FLMDTADR";
}

// docs/telegram-processing.md §2: "The walk reaches an end marker only after every receive
// header before it has been served or missed"; §3: an MST accepted by a header "is withdrawn
// at its detection: VAL is put back as it was and the header waits again". The drive's
// header for the broadcast MDT (ACHK, address 255, TCHK = 0) gets no MDT (the master sends
// its MDT to drive 1) and waits all cycle; the end marker behind it (TEND 1000) is never
// reached, so no INT_ENDMK, though the next MST (address 255) reaches the header.
TEST_P(Cp12, MstTakenByAWaitingHeaderRaisesNoEndMarker) {
  start(0x5001, 0x08FF);
  const std::uint16_t intstat = intstat_of_cycles_1_and_2();
  EXPECT_EQ(intstat & kIntRerr, kIntRerr) << "INT_RERR: the header was missed";
  EXPECT_EQ(intstat & kIntEndmk, 0) << "INT_ENDMK";
}

// Control: the drive's header for its own address, an MDT to it every cycle.
TEST_P(Cp12, ServedHeaderReachesTheEndMarker) {
  start(0x5001, 0x0801);
  const std::uint16_t intstat = intstat_of_cycles_1_and_2();
  EXPECT_EQ(intstat & kIntRerr, 0) << "INT_RERR";
  EXPECT_EQ(intstat & kIntEndmk, kIntEndmk) << "INT_ENDMK";
}

// Control: a header for another drive's address (address 2) is never served either, and
// the MST is no match for it: no INT_ENDMK.
TEST_P(Cp12, UnservedHeaderRaisesNoEndMarker) {
  start(0x5001, 0x0802);
  const std::uint16_t intstat = intstat_of_cycles_1_and_2();
  EXPECT_EQ(intstat & kIntRerr, kIntRerr) << "INT_RERR: the header was missed";
  EXPECT_EQ(intstat & kIntEndmk, 0) << "INT_ENDMK";
}

// Delta spec 2.10.2.2: INT_RSCEND "becomes active, at the end of a receive telegram, if
// there are no service container that need to be worked on or in case the work is
// completed"; 2.11.2 puts it, CLR_RSCEND and EN0/EN1_INT_RSCEND into 28H, one of the
// "SERCON816 NEW Control Registers". The drive's MDT container uses service container 0
// (SVFL): on the 816 INT_RSCEND follows the MDT and drives INT0; the 410B has no 28H, so
// it reads 0 there and INT0 stays inactive, while INT_REND comes on both.
TEST_P(Cp12, ServiceContainerEndIsRaisedOnlyOnThe816) {
  start(0x5001);
  ring.chip(1).ram_write(0x10C, 0x8402);  // LASTDC, SVFL, NSV 0, LEN 2
  ring.chip(1).reg_write(kWdCtrl, kEn0IntRscend);
  run_cycles(2);
  Chip& s = ring.chip(1);
  EXPECT_EQ(s.reg_read(kIntStat) & kIntRend, kIntRend);
  const bool is816 = GetParam() == Variant::Sercon816;
  EXPECT_EQ(s.reg_read(kWdCtrl), is816 ? kEn0IntRscend | kIntRscend : 0);
  EXPECT_EQ(s.pin(Pin::INT0).level(), is816 ? sim::Level::High : sim::Level::Low);
}

INSTANTIATE_TEST_SUITE_P(Variants, Cp12, ::testing::Values(Variant::Sercon816, Variant::Sercon410B),
                         [](const ::testing::TestParamInfo<Variant>& p) {
                           return p.param == Variant::Sercon816 ? "Sercon816" : "Sercon410B";
                         });

}  // namespace
}  // namespace sercon::chip

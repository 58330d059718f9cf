// Phase-up CP0 -> CP4 in a master + slave ring (facts §2 "Phases": CP0 MSTs only, CP1/2 one
// MDT per cycle to one drive which answers, CP3/4 the configured telegrams; facts §5: a
// master switches phases by writing PHAS0, and its layout puts the CP0..2 list at COMPT0 and
// the CP3..4 list at COMPT1). The slave follows the phase of the MSTs it receives (PHASR).
#include <gtest/gtest.h>

#include <array>

#include "telegram_bench.hpp"

namespace sercon::chip {
namespace {

using namespace telegram_testing;

constexpr Time kFibre = 1'000'000;
constexpr std::uint16_t kTscyc = 200;
constexpr std::uint16_t kPhaseReg = 0x0A;  // PHAS0 bits 7..0, PHASR bits 15..8

class PhaseUp : public ::testing::Test {
 protected:
  PhaseUp() : ring(2, kFibre) {
    const Timing t = timing_16mbit();
    ring.run_for(444'444);
    const Time first = ceil_to(ring.scheduler.now(), t.mclk());
    // Where the slave's AT at 120 µs lands on the master's counter (docs/telegram-
    // processing.md §3): the slave's counter loads at its detection of the MST.
    const std::array<std::uint8_t, 1> phase{1};
    const Time mst_in = on_bit_grid(first, t) + kFibre;
    const Time load = detection(mst_in + static_cast<Time>(line_bits(0xFF, phase)) * t.bit, t);
    const Time at_in = on_bit_grid(cycle_time(load, 120, t), t) + kFibre;
    const auto at_time = static_cast<std::uint16_t>(
        t.tcntst + (at_in - first - t.mclkst * t.mclk()) / (t.tick_edges() * t.mclk()));
    // Slave (drive 1). CP0..2 list at 0x100: the AT at 120 µs (sent only when asked,
    // FLMDTADR), then the MDT for drive 1. CP3/4 list at 0x200: the AT at 40 µs, then the
    // MDT to all drives.
    Chip& s = ring.chip(1);
    program_slave(s, t, kTscyc);
    words(s, 0x000, {0x100, 0x200});
    transmit_header(s, 0x100, 0x5001, 120, 2, 0x107);
    words(s, 0x104, {0x8002, 0x0001, 0x0C01});  // status bit 0: present
    receive_header(s, 0x107, 0x0801, 0, 2, 0x110);
    words(s, 0x10C, {0x8002, 0, 0, 0});
    end_marker(s, 0x110, 190);
    transmit_header(s, 0x200, 0x5001, 40, 2, 0x207);
    words(s, 0x204, {0x8002, 0x0003, 0x0C34});
    receive_header(s, 0x207, 0x08FF, 0, 2, 0x210);
    words(s, 0x20C, {0x8002, 0, 0, 0});
    end_marker(s, 0x210, 190);
    enable_transmission(s);
    // Master. CP0..2: the AT in its window (TCHK, ACHK = 0: any drive), then the MDT to
    // drive 1 at 150 µs. CP3/4: the AT of drive 1, then the MDT to all drives at 100 µs.
    Chip& m = ring.chip(0);
    program_master(m, t, kTscyc, 0);
    words(m, 0x000, {0x100, 0x200});
    receive_header(m, 0x100, 0x1000, at_time, 2, 0x109);
    words(m, 0x105, {0x8002, 0, 0, 0});
    transmit_header(m, 0x109, 0x5001, 150, 2, 0x110);
    words(m, 0x10D, {0x8002, 0x0001, 0x0000});
    end_marker(m, 0x110, 190);
    receive_header(m, 0x200, 0x0801, 0, 2, 0x209);
    words(m, 0x205, {0x8002, 0, 0, 0});
    transmit_header(m, 0x209, 0x50FF, 100, 2, 0x210);
    words(m, 0x20D, {0x8002, 0x1234, 0x5678});
    end_marker(m, 0x210, 190);
    start_master(m);
  }

  // Runs `cycles` cycles in `phase` (ENTMT on from CP1) and returns the telegrams that left
  // the master and the slave in them.
  std::pair<std::vector<Seen>, std::vector<Seen>> run_phase(std::uint8_t phase, int cycles) {
    ring.chip(0).reg_write(kPhaseReg, phase);
    if (phase >= 1) ring.chip(0).reg_write(kTpCtrl, kEntmt);
    ring.fibres[0]->seen.clear();
    ring.fibres[1]->seen.clear();
    ring.run_for(cycles * kTscyc * sim::kMicrosecond);
    return {ring.fibres[0]->seen, ring.fibres[1]->seen};
  }

  static std::vector<std::uint8_t> addresses(const std::vector<Seen>& v) {
    std::vector<std::uint8_t> a;
    for (const Seen& s : v) a.push_back(s.address);
    return a;
  }

  Ring ring;
};

TEST_F(PhaseUp, EachPhaseUsesItsListAndTheSlaveFollows) {
  // CP0: MSTs only. The master's ENTMT is off; the slave's is on, but nobody asked it
  // (decision: the FLMDTADR gate holds in phases 0..2, docs/telegram-processing.md §6).
  auto [m0, s0] = run_phase(0, 3);
  EXPECT_EQ(addresses(m0), (std::vector<std::uint8_t>{0xFF, 0xFF, 0xFF}));
  EXPECT_EQ(addresses(s0), (std::vector<std::uint8_t>{0xFF, 0xFF, 0xFF}));  // repeated
  EXPECT_EQ(m0[0].data, std::vector<std::uint8_t>{0});
  // CP1: MST, the MDT to drive 1; the slave repeats both, and answers in the next cycle.
  auto [m1, s1] = run_phase(1, 2);
  EXPECT_EQ(addresses(m1), (std::vector<std::uint8_t>{0xFF, 1, 0xFF, 1}));
  EXPECT_EQ(addresses(s1), (std::vector<std::uint8_t>{0xFF, 1, 0xFF, 1, 1}));
  EXPECT_EQ(ring.chip(1).reg_read(kPhaseReg) >> 8, 1);
  EXPECT_EQ(ring.chip(0).ram_read(0x100), 0x1401);  // the AT's address stored (ACHK = 0)
  EXPECT_EQ(ring.chip(0).ram_read(0x107), 0x0001);
  EXPECT_EQ(ring.chip(0).ram_read(0x108), 0x0C01);
  // CP2: the same list.
  auto [m2, s2] = run_phase(2, 1);
  EXPECT_EQ(addresses(s2), (std::vector<std::uint8_t>{0xFF, 1, 1}));
  EXPECT_EQ(s2[0].data, std::vector<std::uint8_t>{2});
  // CP3 and CP4: COMPT1 in both: the AT first, then the MDT to all drives.
  for (const std::uint8_t phase : {std::uint8_t{3}, std::uint8_t{4}}) {
    auto [m, s] = run_phase(phase, 2);
    EXPECT_EQ(addresses(m), (std::vector<std::uint8_t>{0xFF, 0xFF, 0xFF, 0xFF})) << +phase;
    EXPECT_EQ(m[1].data, (std::vector<std::uint8_t>{0x34, 0x12, 0x78, 0x56}));
    EXPECT_EQ(addresses(s), (std::vector<std::uint8_t>{0xFF, 1, 0xFF, 0xFF, 1, 0xFF})) << +phase;
    EXPECT_EQ(ring.chip(1).reg_read(kPhaseReg) >> 8, phase);
  }
  EXPECT_EQ(ring.chip(0).ram_read(0x207), 0x0003);
  EXPECT_EQ(ring.chip(0).ram_read(0x208), 0x0C34);
  EXPECT_EQ(ring.chip(1).ram_read(0x20E), 0x1234);
  EXPECT_EQ(ring.chip(1).ram_read(0x20F), 0x5678);
  EXPECT_EQ(ring.chip(0).ram_read(10), 0);  // every MST came back
  EXPECT_EQ(ring.chip(1).ram_read(10), 0);  // and reached the slave
}

}  // namespace
}  // namespace sercon::chip

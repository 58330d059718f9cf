// CP4 traffic over the ring layer (sercon::ring::Ring: fibres of different lengths, the
// chips' repeaters), master + 4 slaves (facts §2: MST, ATs at T1, MDT records by position;
// datasheet 4.2; docs/telegram-processing.md). Each node's TxD2 carries the same line as
// its TxD1 and is tapped, so every telegram's start on every node's output is checked to
// the picosecond against the headers, the fibre delays (length x 5 ns/m) and the
// documented receiver / repeater / counter rules.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <memory>
#include <string>
#include <vector>

#include "../chip/line_tee.hpp"
#include "../chip/telegram_bench.hpp"
#include "../ring/ring_bench.hpp"
#include "sercon/ring/ring.hpp"

namespace sercon::chip {
namespace {

using namespace telegram_testing;

constexpr std::size_t kSlaves = 4;
constexpr std::uint16_t kTscyc = 200;
constexpr std::uint16_t kT2 = 90;  // the MDT, on the master's counter
constexpr std::uint16_t kList = 0x040;
const std::vector<double> kLengths{10.0, 20.0, 35.0, 5.0, 40.0};  // fibre i leaves node i

std::uint16_t t1_of(std::size_t k) { return static_cast<std::uint16_t>(20 + 12 * (k - 1)); }

// Logs the start of every telegram on a node's TxD2 when it starts: the announcements
// (line.hpp) go through a SettledLine, so a telegram taken back before it starts (an own
// telegram cutting a repeated one) never appears.
class Tap final : public LineListener {
 public:
  explicit Tap(sim::Scheduler& scheduler) : log_(*this), settled_(scheduler, log_) {}
  Tap(const Tap&) = delete;
  Tap& operator=(const Tap&) = delete;
  void line_condition(Time at, LineCondition condition, Time period) override {
    settled_.line_condition(at, condition, period);
  }
  void line_burst(const LineBurst& burst) override { settled_.line_burst(burst); }
  std::vector<Time> starts;
  std::vector<LineBurst> bursts;  // the same telegrams, with their line bits

 private:
  class Log final : public LineListener {
   public:
    explicit Log(Tap& tap) : tap_(tap) {}
    void line_condition(Time, LineCondition, Time) override {}
    void line_burst(const LineBurst& burst) override {
      tap_.starts.push_back(burst.start);
      tap_.bursts.push_back(burst);
    }

   private:
    Tap& tap_;
  };
  Log log_;
  SettledLine settled_;
};

// Sits between a fibre's far end and a receiver: passes everything on and logs, through a
// Tap, the telegrams that arrive.
using Relay = testing::LineTee<Tap>;

class RingExchange : public ::testing::Test {
 protected:
  RingExchange() : ring(scheduler, ChipConfig{}, ChipConfig{}, kSlaves, options()) {}

  static ring::RingOptions options() {
    ring::RingOptions o;
    o.fibre_lengths_m = kLengths;
    return o;
  }
  // Fibre i's delay from its length (ring_bench.hpp: 5 ns per metre, not read back).
  static Time delay(std::size_t fibre) { return ring::testing::fibre_delay(kLengths[fibre]); }

  void SetUp() override {
    t = timing_16mbit();
    scheduler.run_until(2'222'222);
    first = ceil_to(scheduler.now(), t.mclk());
    expect();
    for (std::size_t k = 1; k <= kSlaves; ++k) program_slave_list(k);
    program_master_list();
    for (std::size_t i = 0; i <= kSlaves; ++i) {
      ring.node(i).reg_write(kSerCtrl, 0x0043);  // TxD1 and TxD2 driven, transmitter on
      taps.push_back(std::make_unique<Tap>(scheduler));
      ring.serial(i).connect_txd(2, *taps.back());
    }
    start_master(ring.master());
  }

  // Passes a telegram that enters node `from` + 1 at `in` on around the ring to the
  // master: records where each node repeats it, returns its arrival at the master.
  Time pass_on(std::size_t from, Time in, std::array<std::vector<Time>, kSlaves + 1>& out) {
    for (std::size_t j = from + 1; j <= kSlaves; ++j) {
      const Time rep = repeated(in, t);
      out[j].push_back(rep);
      in = rep + delay(j);
    }
    return in;
  }

  // Every start on every tap in cycle 0, and the header times, from the rules alone.
  void expect() {
    const std::array<std::uint8_t, 1> phase{4};
    const Time mst_len = static_cast<Time>(line_bits(0xFF, phase)) * t.bit;
    const Time mst = on_bit_grid(first, t);
    starts[0].push_back(mst);
    Time in = mst + delay(0);
    for (std::size_t k = 1; k <= kSlaves; ++k) {
      load[k] = detection(in + mst_len, t);  // the counter loads at the MST's detection
      const Time rep = repeated(in, t);
      starts[k].push_back(rep);
      in = rep + delay(k);
    }
    for (std::size_t k = 1; k <= kSlaves; ++k) {
      const Time at = on_bit_grid(cycle_time(load[k], t1_of(k), t), t);
      starts[k].push_back(at);
      at_time[k] =
          static_cast<std::uint16_t>(counter_at(pass_on(k, at + delay(k), starts), first, t) - 1);
    }
    const Time mdt = on_bit_grid(cycle_time(first, kT2, t), t);
    starts[0].push_back(mdt);
    Time mdt_in = mdt + delay(0);
    for (std::size_t k = 1; k <= kSlaves; ++k) {
      mdt_time[k] = static_cast<std::uint16_t>(counter_at(mdt_in, load[k], t) - 1);
      const Time rep = repeated(mdt_in, t);
      starts[k].push_back(rep);
      mdt_in = rep + delay(k);
    }
    for (auto& s : starts) std::sort(s.begin(), s.end());
  }

  // Slave k: its AT (status, one data word) at T1, its record from the MDT at POS 2(k-1).
  void program_slave_list(std::size_t k) {
    Chip& s = ring.slave(k);
    const auto adr = static_cast<std::uint16_t>(k);
    program_slave(s, t, kTscyc);
    words(s, 0, {0x0060, kList});
    transmit_header(s, kList, static_cast<std::uint16_t>(0x5000 | adr), t1_of(k), 2, 0x047);
    words(s, 0x044,
          {0x8002, static_cast<std::uint16_t>(0x0100 | adr),
           static_cast<std::uint16_t>(0x1000 * adr)});
    receive_header(s, 0x047, 0x18FF, mdt_time[k], 2 * kSlaves, 0x060);
    words(s, 0x04C, {0x8002, static_cast<std::uint16_t>(2 * (k - 1)), 0, 0});
    end_marker(s, 0x060, 180);
    enable_transmission(s);
  }

  // Master: one receive header per AT (ACHK + TCHK), the MDT with one record per drive.
  void program_master_list() {
    Chip& m = ring.master();
    program_master(m, t, kTscyc, 4);
    m.reg_write(kSerMode, 0);  // repeater off (program_master keeps the rate bits: none)
    words(m, 0, {0x0200, kList});
    std::uint16_t at = kList;
    for (std::size_t k = 1; k <= kSlaves; ++k) {
      const auto next = static_cast<std::uint16_t>(at + 9);
      receive_header(m, at, static_cast<std::uint16_t>(0x1800 | k), at_time[k], 2, next);
      words(m, at + 5, {0x8002, 0, 0, 0});
      at = next;
    }
    transmit_header(m, at, 0x50FF, kT2, 2 * kSlaves, static_cast<std::uint16_t>(at + 4 + 12));
    for (std::size_t k = 1; k <= kSlaves; ++k) {
      const auto last = static_cast<std::uint16_t>(k == kSlaves ? 0x8000 : 0);
      words(m, static_cast<std::uint16_t>(at + 4 + 3 * (k - 1)),
            {static_cast<std::uint16_t>(last | 2), static_cast<std::uint16_t>(0xC000 | k),
             static_cast<std::uint16_t>(0xD000 | k)});
    }
    end_marker(m, static_cast<std::uint16_t>(at + 4 + 12), 180);
    end_marker(m, 0x0200, 180);
    enable_transmission(m);
  }

  sim::Scheduler scheduler;
  ring::Ring ring;
  Timing t;
  Time first = 0;
  Time load[kSlaves + 1] = {};
  std::uint16_t at_time[kSlaves + 1] = {};
  std::uint16_t mdt_time[kSlaves + 1] = {};
  std::array<std::vector<Time>, kSlaves + 1> starts;  // expected, cycle 0
  std::vector<std::unique_ptr<Tap>> taps;             // node i's TxD2
};

TEST_F(RingExchange, EveryStartOnEveryNodeIsWhereTheRulesPutIt) {
  scheduler.run_until(first + 2 * kTscyc * sim::kMicrosecond - 1);
  for (std::size_t i = 0; i <= kSlaves; ++i) {
    std::vector<Time> expected = starts[i];
    for (Time s : starts[i]) expected.push_back(s + kTscyc * sim::kMicrosecond);
    EXPECT_EQ(taps[i]->starts, expected) << "node " << i;
  }
}

TEST_F(RingExchange, DataGoesRoundAndNoHeaderReportsAnError) {
  scheduler.run_until(first + 3 * kTscyc * sim::kMicrosecond - 1);
  Chip& m = ring.master();
  for (std::size_t k = 1; k <= kSlaves; ++k) {
    const auto at = static_cast<std::uint16_t>(kList + 9 * (k - 1));
    EXPECT_EQ(m.ram_read(at), 0x1800 | 0x0400 | k) << k;
    EXPECT_EQ(m.ram_read(at + 4), 0) << k;
    EXPECT_EQ(m.ram_read(at + 7), 0x0100 | k) << k;
    EXPECT_EQ(m.ram_read(at + 8), 0x1000 * k) << k;
    Chip& s = ring.slave(k);
    EXPECT_EQ(s.ram_read(0x047), 0x18FF | 0x0400) << k;
    EXPECT_EQ(s.ram_read(0x04E), 0xC000 | k) << k;
    EXPECT_EQ(s.ram_read(0x04F), 0xD000 | k) << k;
    EXPECT_FALSE(s.reg_read(kIntStat) & kIntRerr) << k;
  }
  EXPECT_FALSE(m.reg_read(kIntStat) & kIntRerr);
  EXPECT_EQ(m.ram_read(10), 0);
}

TEST_F(RingExchange, ABrokenFibreCutsTheRingThere) {
  // The fibre from slave 2 to slave 3 breaks: slaves 3 and 4 lose the MST (NMSTERR) and
  // free-wheel on their own µs grid (docs/timing.md), so their ATs still reach the master
  // in their windows; the ATs of slaves 1 and 2 and the master's own MST do not
  // (RERR + NERR, INT_RETMST).
  scheduler.run_until(first + kTscyc * sim::kMicrosecond - 1);
  for (std::size_t i = 0; i <= kSlaves; ++i) {  // what set-up latched (INT_* are W1C)
    Chip& c = i == 0 ? ring.master() : ring.slave(i);
    c.reg_write(kIntStat, kIntFibbr | kIntMstMiss);
  }
  ring.fibre(2).break_now();
  scheduler.run_until(first + 3 * kTscyc * sim::kMicrosecond - 1);
  Chip& m = ring.master();
  // docs/serial-and-ring.md, "Line monitor" and "Repeater": slave 3's RxD is dark, and with
  // the repeater on it darkens every node after it between their own telegrams, so FIBBR
  // latches at slaves 3 and 4 and at the master ("ring open", facts §5), not upstream.
  // INT_MSTMISS (register table: "no MST by the end of the JTSCYC window") at slaves 3 and
  // 4 only.
  EXPECT_TRUE(ring.slave(3).reg_read(kSerCtrl) & kFibbr);  // dark for good
  for (std::size_t i = 0; i <= kSlaves; ++i) {
    Chip& c = i == 0 ? ring.master() : ring.slave(i);
    const bool behind = i == 0 || i >= 3;
    EXPECT_EQ((c.reg_read(kIntStat) & kIntFibbr) != 0, behind) << "node " << i;
    if (i > 0) {
      EXPECT_EQ((c.reg_read(kIntStat) & kIntMstMiss) != 0, i >= 3) << "slave " << i;
    }
  }
  EXPECT_TRUE(m.reg_read(kIntStat) & kIntRetmst);
  // NMSTERR (datasheet 4.2 RAM word 10): JTRDEL2 is 0 (reset value), so a missing MST counts
  // when the next one goes out (docs/telegram-processing.md §3, "Returned MST"): cycle 1's
  // when cycle 2's went out; cycle 2's not yet (cycle 3's goes out after this run).
  EXPECT_EQ(m.ram_read(10), 1);
  for (std::size_t k = 1; k <= kSlaves; ++k) {
    const auto at = static_cast<std::uint16_t>(kList + 9 * (k - 1));
    const bool lost = k <= 2;
    EXPECT_EQ(m.ram_read(at) & 0x2000, lost ? 0x2000 : 0) << k;
    EXPECT_EQ(m.ram_read(at + 4), lost ? 2 : 0) << k;
  }
  EXPECT_EQ(ring.slave(2).ram_read(10), 0);
  EXPECT_EQ(ring.slave(3).ram_read(10), 2);
  EXPECT_EQ(ring.slave(4).ram_read(10), 2);
}

// Facts §5, register 0x04 [seen]: "A driver clears with 0xFFFF, waits 20 cycles and calls
// the ring closed when (reg & 0x0382) == 0" (INT_FIBBR | the JTSCYC window flags). With the
// fibre into the master broken before the clear, the master's RxD stays dark (no slave's
// telegram lights it again, as with a break further up), so the check must fail: INT_FIBBR
// is latched from the FIBBR level and a clear does not stick while it holds
// (docs/serial-and-ring.md, "Line monitor"). Once the fibre is whole again the same check
// passes.
TEST_F(RingExchange, TheDriversRingClosedCheckFailsWhileAFibreIsBroken) {
  constexpr std::uint16_t kRingOpen = 0x0382;
  const Time cycle = kTscyc * sim::kMicrosecond;
  Chip& m = ring.master();
  // The driver's check: clear, wait 20 cycles, read INTSTAT.
  const auto intstat_after_the_check = [&] {
    m.reg_write(kIntStat, 0xFFFF);
    scheduler.run_until(scheduler.now() + 20 * cycle);
    return m.reg_read(kIntStat);
  };
  scheduler.run_until(first + cycle);
  ring.fibre(kSlaves).break_now();
  scheduler.run_until(scheduler.now() + 2 * cycle);
  ASSERT_TRUE(m.reg_read(kSerCtrl) & kFibbr);
  const std::uint16_t open = intstat_after_the_check();
  EXPECT_NE(open & kRingOpen, 0);
  EXPECT_TRUE(open & kIntFibbr);
  ring.fibre(kSlaves).restore();
  scheduler.run_until(scheduler.now() + 2 * cycle);
  ASSERT_FALSE(m.reg_read(kSerCtrl) & kFibbr);
  EXPECT_EQ(intstat_after_the_check() & kRingOpen, 0);
}

// Seeded random line-bit errors on the last fibre (into the master). Which telegrams the
// fibre hit, and where, is read off the line itself: what left slave 4 (its TxD2 tap)
// against what reached the master's RxD (a relay behind the fibre); the levels that differ
// are exactly the fibre's count of flipped bits. Then, cycle by cycle, for each AT k:
// - datasheet 4.2.1 RERR ("errored or not received (RERR = 1)") and NERR (error counter):
//   RERR is set exactly in the cycles AT k was hit and NERR counts exactly those cycles;
// - VAL (single buffer, datasheet 4.2.1: "Modified by controller at beginning and end of
//   receive telegrams"; docs/telegram-processing.md §5): not hit, VAL = 1 and the buffer
//   holds exactly the words slave k sent in that cycle (new words every cycle). Hit after
//   its address (first flipped level 17 or later; a flipped NRZI level changes two line
//   bits), the telegram was taken and ended in error: VAL = 0. Hit in its opening flag or
//   address (first flipped level 15 or earlier), no telegram for the header came: missed
//   ("VAL and the data stay as they are", §5 "Missed"), so VAL and the buffer are as the
//   cycle before left them. So whenever VAL = 1 the buffer holds exactly what slave k sent
//   in its last telegram that arrived intact: a bit error never leaves data marked valid
//   that was not sent;
// - INT_RERR latches in the cycles with a hit AT (docs/telegram-processing.md §10);
// - the master's returning MST, when hit, is not back: NMSTERR + 1 when the next MST goes
//   out (datasheet 4.2 RAM word 10; docs/telegram-processing.md §3 "Returned MST").
TEST_F(RingExchange, BitErrorsOnTheWayCountExactlyTheTelegramsTheyHit) {
  Relay relay(ring.serial(0).rxd(), scheduler);
  ring.fibre(kSlaves).connect(relay);
  ring.fibre(kSlaves).set_bit_error_rate(0.002, 42);
  Chip& m = ring.master();
  auto sent = [](int n, std::size_t k) {
    const auto v = static_cast<std::uint16_t>(static_cast<std::size_t>(n) << 4 | k);
    return std::array<std::uint16_t, 2>{static_cast<std::uint16_t>(0x0100 | v),
                                        static_cast<std::uint16_t>(v * 7 + 0x1000)};
  };
  auto write_at_data = [&](int n) {
    for (std::size_t k = 1; k <= kSlaves; ++k) {
      const auto w = sent(n, k);
      words(ring.slave(k), 0x045, {w[0], w[1]});
    }
  };
  write_at_data(0);
  constexpr int kCycles = 300;
  constexpr std::size_t kPerCycle = 6;  // MST, AT 1..4, MDT, as they leave slave 4
  constexpr std::size_t kNone = ~std::size_t{0};
  const std::vector<LineBurst>& out = taps[kSlaves]->bursts;
  const std::vector<LineBurst>& in = relay.log.bursts;
  std::array<unsigned, kSlaves + 1> nerr{};
  std::array<std::uint16_t, kSlaves + 1> val_before{};  // VAL as the cycle before left it
  std::array<std::array<std::uint16_t, 2>, kSlaves + 1> data_before{};
  unsigned mst_hits = 0, taken_hits = 0, missed_hits = 0;
  std::uint64_t flipped = 0;
  for (int n = 0; n < kCycles; ++n) {
    // After the ATs (the last is in by 70 µs) and the MDT's return, before the end markers.
    scheduler.run_until(first + static_cast<Time>(n) * kTscyc * sim::kMicrosecond +
                        150 * sim::kMicrosecond);
    const auto cycle_size = kPerCycle * static_cast<std::size_t>(n + 1);
    ASSERT_EQ(out.size(), cycle_size) << "cycle " << n;
    ASSERT_EQ(in.size(), cycle_size) << "cycle " << n;
    std::array<std::size_t, kPerCycle> first_flip{};
    for (std::size_t j = 0; j < kPerCycle; ++j) {
      const LineBurst& a = out[cycle_size - kPerCycle + j];
      const LineBurst& b = in[cycle_size - kPerCycle + j];
      ASSERT_EQ(b.start, a.start + delay(kSlaves)) << "cycle " << n << " telegram " << j;
      ASSERT_EQ(b.bits->size(), a.bits->size());
      first_flip[j] = kNone;
      for (std::size_t i = 0; i < a.bits->size(); ++i) {
        if (a.bits->level(i) == b.bits->level(i)) continue;
        if (first_flip[j] == kNone) first_flip[j] = i;
        ++flipped;
      }
    }
    EXPECT_EQ(m.ram_read(10), mst_hits) << "NMSTERR, cycle " << n;  // MSTs of cycles before n
    mst_hits += first_flip[0] != kNone ? 1u : 0u;
    bool any = false;
    for (std::size_t k = 1; k <= kSlaves; ++k) {
      const std::size_t flip = first_flip[k];
      const bool hit = flip != kNone;
      any = any || hit;
      nerr[k] += hit ? 1u : 0u;
      const auto at = static_cast<std::uint16_t>(kList + 9 * (k - 1));
      const std::uint16_t word0 = m.ram_read(at);
      const std::uint16_t val = word0 & 0x0400;
      const std::array<std::uint16_t, 2> data{m.ram_read(static_cast<std::uint16_t>(at + 7)),
                                              m.ram_read(static_cast<std::uint16_t>(at + 8))};
      const std::string where = "cycle " + std::to_string(n) + " AT " + std::to_string(k) +
                                " first flipped level " + std::to_string(flip);
      EXPECT_EQ((word0 & 0x2000) != 0, hit) << "RERR, " << where;
      EXPECT_EQ(word0 & 0x1BFF, 0x1800 | k) << where;  // ADR, ACHK, TCHK as set
      EXPECT_EQ(m.ram_read(at + 4), nerr[k]) << "NERR, " << where;
      if (!hit) {
        EXPECT_EQ(val, 0x0400) << "VAL, " << where;
        EXPECT_EQ(data, sent(n, k)) << where;
      } else if (flip >= 17) {
        EXPECT_EQ(val, 0) << "VAL, " << where;
        ++taken_hits;
      } else if (flip <= 15) {
        EXPECT_EQ(val, val_before[k]) << "VAL, " << where;
        EXPECT_EQ(data, data_before[k]) << where;
        ++missed_hits;
      }
      val_before[k] = val;
      data_before[k] = data;
    }
    EXPECT_EQ((m.reg_read(kIntStat) & kIntRerr) != 0, any) << "INT_RERR, cycle " << n;
    m.reg_write(kIntStat, kIntRerr);
    write_at_data(n + 1);
  }
  EXPECT_EQ(flipped, ring.fibre(kSlaves).bit_errors());
  // The seed gives enough of each case to mean something (p = 0.002 over ~80-bit ATs).
  EXPECT_GT(taken_hits, 50u);
  EXPECT_GT(missed_hits, 10u);
  EXPECT_GT(mst_hits, 10u);
  ring.fibre(kSlaves).disconnect();
}

}  // namespace
}  // namespace sercon::chip

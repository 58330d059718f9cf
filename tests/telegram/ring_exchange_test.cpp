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
#include <vector>

#include "../chip/telegram_bench.hpp"
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

std::uint16_t counter_at(Time at, Time load, const Timing& t) {
  const Time first_tick = load + t.mclkst * t.mclk();
  if (at < first_tick) return t.tcntst;
  return static_cast<std::uint16_t>(t.tcntst + (at - first_tick) / (t.tick_edges() * t.mclk()) + 1);
}

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

 private:
  class Log final : public LineListener {
   public:
    explicit Log(Tap& tap) : tap_(tap) {}
    void line_condition(Time, LineCondition, Time) override {}
    void line_burst(const LineBurst& burst) override { tap_.starts.push_back(burst.start); }

   private:
    Tap& tap_;
  };
  Log log_;
  SettledLine settled_;
};

class RingExchange : public ::testing::Test {
 protected:
  RingExchange() : ring(scheduler, ChipConfig{}, ChipConfig{}, kSlaves, options()) {}

  static ring::RingOptions options() {
    ring::RingOptions o;
    o.fibre_lengths_m = kLengths;
    return o;
  }
  Time delay(std::size_t fibre) { return ring.fibre(fibre).delay(); }

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
  EXPECT_GE(m.ram_read(10), 1);
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

TEST_F(RingExchange, BitErrorsOnTheWayShowAsRerrAndNerr) {
  // Seeded random line-bit errors on the last fibre (into the master): every AT that
  // arrives errored counts once in its header's NERR.
  ring.fibre(kSlaves).set_bit_error_rate(0.002, 42);
  scheduler.run_until(first + 50 * kTscyc * sim::kMicrosecond - 1);
  Chip& m = ring.master();
  unsigned nerr = 0;
  for (std::uint16_t at = kList; at < kList + 9 * kSlaves; at += 9) nerr += m.ram_read(at + 4);
  EXPECT_GT(ring.fibre(kSlaves).bit_errors(), 0u);
  EXPECT_GT(nerr, 0u);
  EXPECT_LE(nerr, ring.fibre(kSlaves).bit_errors());
  EXPECT_TRUE(m.reg_read(kIntStat) & kIntRerr);
}

}  // namespace
}  // namespace sercon::chip

// Lazy hops (docs/serial-and-ring.md, "Lazy hops") are a speed option: a node that would
// only pass a telegram on keeps the bare burst and takes it into its timelines when
// something asks. They must change nothing anyone can see. Each test runs the same CP4
// ring (master + 4 slaves, tests/chip/cp4_ring.hpp) twice, lazy hops on and off, does the
// same things to it at the same times, and compares everything observable:
// - the line at the master's RxD, change by change at the moment it happens (a tap behind
//   the last fibre; every telegram of the cycle crosses it);
// - BUSYN, INT0 and INT1 of every chip at every edge (the telegram processors' DPRAM work
//   and interrupts, to the picosecond);
// - DPRAM words 0x000-0x07F of every chip (fixed words, lists, headers, data) every 2 µs.
// Each trigger that makes a node take its lazy bursts in (docs, "Lazy hops") has a test
// that pulls it while bursts are lazy: an own telegram (every cycle), a change of the
// telegram processor's interest (every cycle), RECACT read, RECACTN watched, REPON written,
// a fibre broken and restored, a listener joining a TxD.
#include <gtest/gtest.h>

#include <algorithm>
#include <functional>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "../chip/cp4_ring.hpp"
#include "../chip/line_tee.hpp"
#include "sercon/chip/serial_unit_fields.hpp"
#include "sercon/chip/settled_line.hpp"

namespace sercon::chip {
namespace {

using namespace telegram_testing;

constexpr std::size_t kSlaves = 4;
constexpr std::size_t kCycles = 10;

using Trace = std::vector<std::string>;

// Logs each change of a line when it happens (settled: what is in force at that time).
class SettledTrace final : public LineListener {
 public:
  SettledTrace(sim::Scheduler& s, Trace& trace) : log_(s, trace), settled_(s, log_) {}
  void line_condition(sim::Time at, LineCondition c, sim::Time period) override {
    settled_.line_condition(at, c, period);
  }
  void line_burst(const LineBurst& b) override { settled_.line_burst(b); }

 private:
  class Log final : public LineListener {
   public:
    Log(sim::Scheduler& s, Trace& trace) : s_(s), trace_(trace) {}
    void line_condition(sim::Time at, LineCondition c, sim::Time period) override {
      trace_.push_back(std::to_string(s_.now()) + " RxD " + std::string(to_string(c)) + " at " +
                       std::to_string(at) + " period " + std::to_string(period));
    }
    void line_burst(const LineBurst& b) override {
      std::string bits;
      for (std::size_t i = 0; i < b.bits->size(); ++i) bits += (*b.bits)[i] ? '1' : '0';
      trace_.push_back(std::to_string(s_.now()) + " RxD burst at " + std::to_string(b.start) + " " +
                       bits);
    }

   private:
    sim::Scheduler& s_;
    Trace& trace_;
  };
  Log log_;
  SettledLine settled_;
};

// Passes the last fibre's line on to the master's RxD and logs each change when it happens.
using MasterTap = testing::LineTee<SettledTrace>;

// A listener on a TxD that logs what it is told, when it is told.
class Heard final : public LineListener {
 public:
  Heard(sim::Scheduler& s, Trace& trace, std::string name)
      : s_(s), trace_(trace), name_(std::move(name)) {}
  void line_condition(sim::Time at, LineCondition c, sim::Time period) override {
    trace_.push_back(std::to_string(s_.now()) + " " + name_ + " " + std::string(to_string(c)) +
                     " at " + std::to_string(at) + " period " + std::to_string(period));
  }
  void line_burst(const LineBurst& b) override {
    trace_.push_back(std::to_string(s_.now()) + " " + name_ + " burst at " +
                     std::to_string(b.start) + " bits " + std::to_string(b.bits->size()));
  }

 private:
  sim::Scheduler& s_;
  Trace& trace_;
  std::string name_;
};

// One run: the ring, what is recorded, and what the scenario records itself.
struct RingRun {
  explicit RingRun(bool lazy) {
    ring::Ring& r = cp4.ring();
    for (std::size_t i = 0; i <= kSlaves; ++i) r.serial(i).set_lazy_hops(lazy);
    tap = std::make_unique<MasterTap>(r.serial(0).rxd(), cp4.scheduler(), trace);
    r.fibre(kSlaves).connect(*tap);
    for (std::size_t i = 0; i <= kSlaves; ++i) {
      for (const Pin p : {Pin::BUSYN, Pin::INT0, Pin::INT1}) {
        r.node(i).pin(p).watch([this, i, p](sim::Level level) {
          trace.push_back(std::to_string(cp4.scheduler().now()) + " node " + std::to_string(i) +
                          " " + std::string(pin_name(p)) + " " +
                          std::to_string(static_cast<int>(level)));
        });
      }
    }
  }
  // Runs the cycles, a data change per cycle, sampling DPRAM every 2 µs.
  void run() {
    std::uint16_t value = 0x1234;
    for (std::size_t c = 0; c < kCycles; ++c) {
      cp4.change_data(++value);
      const sim::Time end = cp4.scheduler().now() + static_cast<sim::Time>(cp4.cycle_ps());
      for (sim::Time t = cp4.scheduler().now(); t < end; t += 2 * sim::kMicrosecond) {
        cp4.scheduler().run_until(t);
        sample_ram();
      }
      cp4.scheduler().run_until(end);
    }
  }
  void sample_ram() {
    std::string words = std::to_string(cp4.scheduler().now()) + " RAM";
    for (std::size_t i = 0; i <= kSlaves; ++i) {
      for (std::uint16_t a = 0; a < 0x80; ++a) {
        words += ' ' + std::to_string(cp4.ring().node(i).ram_read(a));
      }
    }
    if (words.substr(words.find(' ')) != last_ram_) {
      last_ram_ = words.substr(words.find(' '));
      trace.push_back(std::move(words));
    }
  }
  std::uint64_t lazy_hops() {
    std::uint64_t n = 0;
    for (std::size_t i = 0; i <= kSlaves; ++i) n += cp4.ring().serial(i).lazy_hops_taken();
    return n;
  }
  void record(const std::string& what) {
    trace.push_back(std::to_string(cp4.scheduler().now()) + " " + what);
  }

  // The TxD listeners and the trace outlive the chips that call them; the tap goes before
  // the scheduler its SettledLine plans on (nothing calls it while the ring is taken down).
  Trace trace;
  std::vector<std::unique_ptr<LineListener>> listeners;
  std::string last_ram_;
  Cp4Ring cp4{layout_for(kSlaves, 250)};
  std::unique_ptr<MasterTap> tap;
};

// Builds both runs, lets `scenario` set up the same actions on each, runs them, and
// compares. The lazy run must have taken lazy hops, the other none.
// Returns what cp4_ring.hpp's end-to-end check says of the lazy run (empty: data arrived).
std::string same_either_way(const std::function<void(RingRun&)>& scenario,
                            std::uint64_t min_lazy_hops = 4 * kCycles) {
  RingRun lazy(true), full(false);
  scenario(lazy);
  scenario(full);
  lazy.run();
  full.run();
  // Undisturbed, 6 ATs per cycle pass slaves downstream of their sender.
  EXPECT_GE(lazy.lazy_hops(), min_lazy_hops);
  EXPECT_EQ(full.lazy_hops(), 0u);
  EXPECT_EQ(lazy.trace.size(), full.trace.size());
  for (std::size_t i = 0; i < std::min(lazy.trace.size(), full.trace.size()); ++i) {
    EXPECT_EQ(lazy.trace[i], full.trace[i]) << "first difference at entry " << i;
    if (lazy.trace[i] != full.trace[i]) break;
  }
  return lazy.cp4.data_arrived(0x1234 + kCycles) + lazy.cp4.headers_clean();
}

// A time in cycle `c` (counted from the start of the runs) at `us` µs.
sim::Time in_cycle(RingRun& r, std::size_t c, double us) {
  return r.cp4.scheduler().now() + static_cast<sim::Time>(c * r.cp4.cycle_ps()) +
         static_cast<sim::Time>(us * sim::kMicrosecond);
}

// Own telegrams (each slave's AT cuts into what it repeats) and the telegram processors'
// interest (list moves, every report) pull lazy bursts in every cycle.
TEST(LazyHops, ACp4RingRunsTheSameWithAndWithout) {
  EXPECT_EQ(same_either_way([](RingRun&) {}), "");
}

// The triggers below are pulled on slave 3 with its transmission off (register 0x03 ENTMT
// = 0): it sends no AT of its own, which would otherwise take in the ATs of slaves 1 and 2
// that passed it lazily just before, so they stay lazy until the trigger comes.
void quiet_slave_3(RingRun& r) { r.cp4.ring().node(3).reg_write(kTpCtrl, 0); }

// Datasheet Table 1 / register 0x02 RECACT: reading it takes the lazy bursts in first.
TEST(LazyHops, RecactReadWhileTelegramsPassGivesTheSameValues) {
  same_either_way([](RingRun& r) {
    quiet_slave_3(r);
    const FieldRef recact = r.cp4.ring().serial(3).fields().recact;
    for (int k = 0; k < 400; ++k) {
      r.cp4.scheduler().at(in_cycle(r, 4, 15.0 + 0.25 * k), [&r, recact] {
        r.record("RECACT " +
                 std::to_string(r.cp4.ring().node(3).reg_read(recact.address) & recact.mask));
      });
    }
  });
}

// Datasheet Table 1 RECACTN: a watcher joining sees the level then and every edge while it
// watches; here one joins and leaves every 3 µs through two cycles.
TEST(LazyHops, RecactnWatchedOnAndOffShowsTheSameEdges) {
  same_either_way([](RingRun& r) {
    quiet_slave_3(r);
    for (int k = 0; k < 160; ++k) {
      const sim::Time from = in_cycle(r, 4, 3.0 * k);
      r.cp4.scheduler().at(from, [&r] {
        sim::Signal& pin = r.cp4.ring().node(3).pin(Pin::RECACTN);
        const std::size_t handle = pin.watch([&r](sim::Level level) {
          r.record("RECACTN " + std::to_string(static_cast<int>(level)));
        });
        r.record("RECACTN is " + std::to_string(static_cast<int>(pin.level())));
        r.cp4.scheduler().after(sim::kMicrosecond, [&pin, handle] { pin.unwatch(handle); });
      });
    }
  });
}

// Delta spec 2.3.3 (REPON): switched off while ATs pass, and on again a cycle later.
TEST(LazyHops, RepeaterSwitchedOffAndOnGivesTheSameLine) {
  same_either_way([](RingRun& r) {
    quiet_slave_3(r);
    const FieldRef repon = r.cp4.ring().serial(3).fields().repon;
    const auto set = [&r, repon](bool on) {
      Chip& c = r.cp4.ring().node(3);
      const std::uint16_t v = c.reg_read(repon.address);
      c.reg_write(repon.address, static_cast<std::uint16_t>(on ? v | repon.mask : v & ~repon.mask));
    };
    r.cp4.scheduler().at(in_cycle(r, 3, 41.0), [set] { set(false); });
    r.cp4.scheduler().at(in_cycle(r, 4, 43.0), [set] { set(true); });
  });
}

// A fibre broken while ATs pass its sender lazily, and restored later (docs/serial-and-
// ring.md, "Fibre": a broken fibre passes nothing on).
TEST(LazyHops, AFibreBrokenAndRestoredGivesTheSameLine) {
  same_either_way([](RingRun& r) {
    quiet_slave_3(r);
    r.cp4.ring().fibre(2).break_at(in_cycle(r, 4, 10.0));
    r.cp4.ring().fibre(2).restore_at(in_cycle(r, 4, 60.0));
    r.cp4.ring().fibre(3).break_at(in_cycle(r, 5, 30.0));
    r.cp4.ring().fibre(3).restore_at(in_cycle(r, 5, 130.0));
  });
}

// Seeded bit errors on a fibre (docs/serial-and-ring.md, "Fibre"): every telegram that
// crosses it gets its own flips, so nothing passes it lazily.
TEST(LazyHops, BitErrorsOnAFibreGiveTheSameLine) {
  same_either_way([](RingRun& r) { r.cp4.ring().fibre(3).set_bit_error_rate(2e-3, 77); }, 10);
}

// Datasheet Table 1 TxD2 / register 0x02 TXOE: a second output switched on mid-cycle, with
// a listener, is told the line from then on; the node then has two listeners (no lazy hop).
TEST(LazyHops, AListenerJoiningATxdGetsTheSameLine) {
  same_either_way([](RingRun& r) {
    quiet_slave_3(r);
    r.cp4.scheduler().at(in_cycle(r, 4, 44.0), [&r] {
      Chip& c = r.cp4.ring().node(3);
      c.reg_write(kSerCtrl, static_cast<std::uint16_t>(c.reg_read(kSerCtrl) | 0x0002));
    });
    r.cp4.scheduler().at(in_cycle(r, 4, 52.5), [&r] {
      r.listeners.push_back(std::make_unique<Heard>(r.cp4.scheduler(), r.trace, "TxD2"));
      r.cp4.ring().serial(3).connect_txd(2, *r.listeners.back());
    });
  });
}

// Everything above at once, at random times on random nodes, for a handful of seeds (slave 3
// quiet in every other one): RECACT reads, RECACTN watched and let go, REPON off and on,
// TxD2 switched on and off with a listener joining and leaving, the bit rate changed and
// back, fibres broken and restored. Whatever the actions do to the ring, lazy hops must not
// change what anyone sees.
class LazyHopsRandom : public ::testing::TestWithParam<std::uint32_t> {};

void random_actions(RingRun& r, std::uint32_t seed) {
  std::mt19937 rng(seed);
  const auto pick = [&rng](std::size_t n) {
    return static_cast<std::size_t>(std::uniform_int_distribution<std::size_t>(0, n - 1)(rng));
  };
  const sim::Time span = static_cast<sim::Time>(kCycles * r.cp4.cycle_ps());
  const sim::Time base = r.cp4.scheduler().now();
  for (int k = 0; k < 24; ++k) {
    const sim::Time at =
        base + std::uniform_int_distribution<sim::Time>(sim::kMicrosecond, span - 1)(rng);
    const std::size_t node = pick(kSlaves + 1);
    ring::Ring& ring = r.cp4.ring();
    switch (pick(7)) {
      case 0:
        r.cp4.scheduler().at(at, [&r, node] {
          const FieldRef recact = r.cp4.ring().serial(node).fields().recact;
          r.record("node " + std::to_string(node) + " RECACT " +
                   std::to_string(r.cp4.ring().node(node).reg_read(recact.address) & recact.mask));
        });
        break;
      case 1: {
        const sim::Time until = at + std::uniform_int_distribution<sim::Time>(1, 30'000'000)(rng);
        r.cp4.scheduler().at(at, [&r, node, until] {
          sim::Signal& pin = r.cp4.ring().node(node).pin(Pin::RECACTN);
          const std::size_t handle = pin.watch([&r, node](sim::Level level) {
            r.record("node " + std::to_string(node) + " RECACTN " +
                     std::to_string(static_cast<int>(level)));
          });
          r.cp4.scheduler().at(until, [&pin, handle] { pin.unwatch(handle); });
        });
        break;
      }
      case 2:    // REPON flipped, and back later
      case 3: {  // TxD2's output enable (register 0x02 bit 1) flipped, and back later
        const FieldRef repon = ring.serial(node).fields().repon;
        const bool is_repon = k % 2 == 0;
        const std::uint8_t address = is_repon ? repon.address : std::uint8_t{kSerCtrl};
        const std::uint16_t mask = is_repon ? repon.mask : std::uint16_t{0x0002};
        const auto flip = [&r, node, address, mask] {
          Chip& c = r.cp4.ring().node(node);
          c.reg_write(address, static_cast<std::uint16_t>(c.reg_read(address) ^ mask));
        };
        r.cp4.scheduler().at(at, flip);
        r.cp4.scheduler().at(at + std::uniform_int_distribution<sim::Time>(1, 60'000'000)(rng),
                             flip);
        break;
      }
      case 4:
        r.cp4.scheduler().at(at, [&r, node] {
          r.listeners.push_back(std::make_unique<Heard>(r.cp4.scheduler(), r.trace,
                                                        "node " + std::to_string(node) + " TxD2"));
          r.cp4.ring().serial(node).connect_txd(2, *r.listeners.back());
        });
        r.cp4.scheduler().at(at + std::uniform_int_distribution<sim::Time>(1, 50'000'000)(rng),
                             [&r, node] { r.cp4.ring().serial(node).disconnect_txd(2); });
        break;
      case 5: {  // the bit rate switched to 2 Mbit/s (0x01 ENTSBAUD, SWBAUD16, SWBAUD), and back
        const auto flip = [&r, node] {
          Chip& c = r.cp4.ring().node(node);
          c.reg_write(kSerMode, static_cast<std::uint16_t>(c.reg_read(kSerMode) ^
                                                           (kEntsbaud | kSwbaud16 | kSwbaud)));
        };
        r.cp4.scheduler().at(at, flip);
        r.cp4.scheduler().at(at + std::uniform_int_distribution<sim::Time>(1, 30'000'000)(rng),
                             flip);
        break;
      }
      default: {
        ring::Fibre& f = ring.fibre(node);
        f.break_at(at);
        f.restore_at(at + std::uniform_int_distribution<sim::Time>(1, 40'000'000)(rng));
        break;
      }
    }
  }
}

TEST_P(LazyHopsRandom, AnyMixOfActionsGivesTheSameRing) {
  const std::uint32_t seed = GetParam();
  same_either_way(
      [seed](RingRun& r) {
        if (seed % 2 == 0) quiet_slave_3(r);
        random_actions(r, seed);
      },
      10);
}

INSTANTIATE_TEST_SUITE_P(Seeds, LazyHopsRandom, ::testing::Range(1u, 9u));

}  // namespace
}  // namespace sercon::chip

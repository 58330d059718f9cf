// Lazy bursts left waiting by plans that want none of their reports (docs/serial-and-ring.md,
// "Lazy hops" and "Absorbing": the results are those of the full path): differential
// scenarios, lazy hops on and off, with a ReceiveInterest the test controls: the interest
// switched on while bursts of 1-4 frames wait lazily, plans that leave them lazy followed by
// each trigger (RECACT read, a cut, rate, SWRST, REPON, a TxD joining, an own telegram, a
// superseding burst, a handler or the interest removed and restored), and the error of a
// ring where every node repeats ("Depth guard"). Written as a review of the change that let
// plans leave bursts lazy; SERCON_REVIEW_DUMP=file writes every full-path log there, to
// compare two builds (before and after that change gave byte-identical dumps).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <string>
#include <vector>

#include "repeating_chip.hpp"
#include "ring_bench.hpp"
#include "sercon/chip/chip.hpp"
#include "sercon/chip/serial_unit.hpp"
#include "sercon/chip/serial_unit_fields.hpp"
#include "sercon/chip/serial_unit_receiver.hpp"
#include "sercon/ring/fibre.hpp"
#include "sercon/ring/ring.hpp"
#include "sercon/wire/encoder.hpp"

namespace sercon::ring {
namespace {

using sim::Time;

// SERCON_REVIEW_DUMP=file: every run's log goes there too (to compare builds).
void dump(const std::vector<std::string>& log, const std::string& what) {
  static const char* path = std::getenv("SERCON_REVIEW_DUMP");
  if (path == nullptr) return;
  static std::ofstream out(path);
  out << "== " << what << "\n";
  for (const auto& l : log) out << l << "\n";
}
using testing::config_at_mbit;
constexpr Time kBit = 62'500;

using testing::set_bits;

struct Want final : chip::ReceiveInterest {
  bool start = false, tel = false;
  bool wants_start(Time, std::uint8_t) const override { return start; }
  bool wants_telegram(Time, const wire::DecodedFrame&) const override { return tel; }
};

chip::SharedBits frames_bits(int n) {
  wire::LineEncoder enc(true);
  for (int i = 0; i < n; ++i) {
    const std::uint8_t d[2] = {0x55, 0xAA};
    enc.telegram(static_cast<std::uint8_t>(0x10 + i), d);
  }
  return chip::share_bits(enc.take());
}

// Idle at the bit rate, then twelve bursts of `frames` frames announced ahead, 20 bits
// apart; gives the first burst's start, the bits from one start to the next and the bursts'
// bits.
struct Bursts {
  Time base, len;
  chip::SharedBits bits;
};
Bursts announce_twelve_bursts(sim::Scheduler& s, chip::SerialUnit& u, int frames) {
  s.run_until(1000 * kBit);
  u.rxd().line_condition(s.now(), chip::LineCondition::Idle, kBit);
  s.run_until(s.now() + 100 * kBit);
  const Time base = s.now() + 10 * kBit;
  const chip::SharedBits bits = frames_bits(frames);
  const Time len = static_cast<Time>(bits->size()) + 20;
  for (int i = 0; i < 12; ++i)
    u.rxd().line_burst(chip::LineBurst{base + i * len * kBit, kBit, bits});
  return {base, len, bits};
}

// mode bits: 1 = start wanted when switched on, 2 = telegram wanted, 4 = drop a handler
// instead of switching interest, 8 = switch back off later.
std::uint64_t hops = 0;
std::size_t waiting = 0;
std::vector<std::string> run(bool lazy, int frames, Time switch_bits, int mode) {
  testing::RepeatingChip node(lazy);
  sim::Scheduler& s = node.s;
  chip::SerialUnit& u = node.u;
  testing::Recorder sink(s);
  Fibre f(s, 10.0);
  node.repeat_into(f, sink);
  std::vector<std::string> log;
  Want want;
  u.set_interest(&want);
  u.on_telegram_start([&](Time st, std::uint8_t a) {
    log.push_back(std::to_string(s.now()) + " start " + std::to_string(st) + " " +
                  std::to_string(a));
  });
  u.on_telegram([&](const chip::ReceivedTelegram& t) {
    log.push_back(std::to_string(s.now()) + " tel " + std::to_string(t.start) + " " +
                  std::to_string(t.end));
  });
  const Bursts bursts = announce_twelve_bursts(s, u, frames);
  const Time base = bursts.base, len = bursts.len;
  s.run_until(base + switch_bits * kBit / 4);
  hops = u.lazy_hops_taken();
  waiting = u.receiver().lazy_bursts_waiting();
  if (mode & 4) {
    u.on_telegram_start({});
  } else {
    want.start = mode & 1;
    want.tel = mode & 2;
    u.interest_changed();
  }
  if (mode & 8) {
    s.run_until(s.now() + 37 * kBit);
    want.start = want.tel = false;
    u.interest_changed();
    s.run_until(s.now() + 200 * kBit);
    want.start = want.tel = true;
    u.interest_changed();
  }
  s.run_until(base + 14 * len * kBit);
  for (const auto& e : sink.events)
    log.push_back("sink " + std::to_string(e.now) + " " + std::to_string(e.at));
  return log;
}

TEST(LazyHopsReview, InterestSwitchedOnWhileBurstsWaitReportsTheSame) {
  for (int frames : {1, 2, 3, 4}) {
    for (int mode : {1, 2, 3, 4 | 3, 8 | 3, 8 | 1, 8 | 2}) {
      for (Time sw = 0; sw < 4 * 3 * 120; sw += 3) {
        const auto a = run(true, frames, sw, mode), b = run(false, frames, sw, mode);
        if (sw == 300 && mode == 3) {
          run(true, frames, sw, mode);
          EXPECT_GT(waiting, 1u);  // bursts were still lazy when the interest changed
        }
        dump(b, "frames " + std::to_string(frames) + " mode " + std::to_string(mode) + " sw " +
                    std::to_string(sw));
        ASSERT_EQ(a, b) << "frames " << frames << " mode " << mode << " switch " << sw;
      }
    }
  }
}

}  // namespace
}  // namespace sercon::ring

namespace sercon::ring {
namespace {

// Plans that keep the bursts lazy (interest_changed every 11 bits, nothing wanted), an
// action at `when` (quarter bits), then everything wanted 50 bits later.
std::vector<std::string> pulses_then(bool lazy, int frames, Time when, int action) {
  testing::RepeatingChip node(lazy);
  sim::Scheduler& s = node.s;
  chip::Chip& c = node.c;
  chip::SerialUnit& u = node.u;
  testing::Recorder out1(s), out2(s);
  Fibre f(s, 10.0);
  node.repeat_into(f, out1);
  std::vector<std::string> log;
  for (const chip::Pin p : {chip::Pin::TxD1, chip::Pin::TxD2, chip::Pin::L_ERRN, chip::Pin::IDLE}) {
    c.pin(p).watch([&log, &s, p](sim::Level l) {
      log.push_back(std::to_string(s.now()) + " pin " + std::string(chip::pin_name(p)) + " " +
                    std::to_string(static_cast<int>(l)));
    });
  }
  Want want;
  u.set_interest(&want);
  const auto start_h = [&](Time st, std::uint8_t a) {
    log.push_back(std::to_string(s.now()) + " start " + std::to_string(st) + " " +
                  std::to_string(a));
  };
  u.on_telegram_start(start_h);
  u.on_telegram([&](const chip::ReceivedTelegram& t) {
    log.push_back(std::to_string(s.now()) + " tel " + std::to_string(t.start) + " " +
                  std::to_string(t.end) + " " + std::to_string(t.detected));
  });
  const Bursts bursts = announce_twelve_bursts(s, u, frames);
  const Time base = bursts.base, len = bursts.len;
  const chip::SharedBits& bits = bursts.bits;
  for (Time k = 1; k < 12 * len / 11; ++k)
    s.at(base + k * 11 * kBit, [&] { u.interest_changed(); });
  s.at(base + when * kBit / 4, [&] {
    waiting = std::max(waiting, u.receiver().lazy_bursts_waiting());
    const auto flip = [&c](std::uint8_t a, std::uint16_t m) {
      c.reg_write(a, static_cast<std::uint16_t>(c.regs().value(a) ^ m));
    };
    switch (action) {
      case 0:
        log.push_back("recact " + std::to_string(c.reg_read(u.fields().recact.address)));
        break;
      case 1:
        u.rxd().line_condition(s.now() + 7 * kBit, chip::LineCondition::Idle, kBit);
        break;
      case 2:
        flip(0x01, static_cast<std::uint16_t>((1u << 10) | (1u << 6)));
        break;
      case 3:
        c.reg_write(0x01, static_cast<std::uint16_t>(c.regs().value(0x01) | 2u));
        break;
      case 4:
        flip(0x01, 1u << 3);
        break;
      case 5:
        c.reg_write(0x02, 0x0043);
        u.connect_txd(2, out2);
        break;
      case 6:
        u.send(u.next_bit_edge(s.now() + 5 * kBit), 0x09, std::vector<std::uint8_t>{1, 2});
        break;
      case 7:
        u.rxd().line_burst(chip::LineBurst{s.now() + 3 * kBit, kBit, bits});
        break;
      case 8:
        u.on_telegram_start({});
        break;
      case 9:
        u.set_interest(nullptr);
        break;
      case 10:
        u.on_telegram_start({});
        s.at(s.now() + 23 * kBit, [&] { u.on_telegram_start(start_h); });
        break;
      case 11:
        u.set_interest(nullptr);
        s.at(s.now() + 23 * kBit, [&] { u.set_interest(&want); });
        break;
      case 12:
        u.on_telegram({});
        s.at(s.now() + 23 * kBit, [&] {
          u.on_telegram([&](const chip::ReceivedTelegram& t) {
            log.push_back(std::to_string(s.now()) + " tel2 " + std::to_string(t.start));
          });
        });
        break;
      default:
        break;
    }
    log.push_back(std::to_string(s.now()) + " action");
  });
  s.at(base + when * kBit / 4 + 50 * kBit, [&] {
    want.start = want.tel = true;
    u.interest_changed();
  });
  s.run_until(base + 14 * len * kBit);
  log.push_back("recact end " + std::to_string(c.reg_read(u.fields().recact.address)));
  for (const auto& e : out1.events)
    log.push_back("TxD1 " + std::to_string(e.now) + " " + std::to_string(e.at) + " " +
                  std::to_string(e.burst));
  for (const auto& e : out2.events)
    log.push_back("TxD2 " + std::to_string(e.now) + " " + std::to_string(e.at) + " " +
                  std::to_string(e.burst));
  return log;
}

TEST(LazyHopsReview, ActionsAfterPlansThatLeftTheBurstsLazy) {
  waiting = 0;
  for (int frames : {1, 3}) {
    for (int action = 0; action < 13; ++action) {
      for (Time w = 0; w < 4 * 400; w += 5) {
        const auto a = pulses_then(true, frames, w, action),
                   b = pulses_then(false, frames, w, action);
        dump(b, "frames " + std::to_string(frames) + " action " + std::to_string(action) + " w " +
                    std::to_string(w));
        ASSERT_EQ(a, b) << "frames " << frames << " action " << action << " when " << w;
      }
    }
  }
  EXPECT_GT(waiting, 1u);  // the plans did leave bursts lazy
}

}  // namespace
}  // namespace sercon::ring

namespace sercon::ring {
namespace {

// The error of a ring where every node repeats (lazy_hops_node_test.cpp): the same error,
// at the same moment, lazy or not (kMaxTimeline counts entries that prune_lazy may drop).
std::string circling_error(bool lazy, Time insert_after_bits) {
  sim::Scheduler s;
  RingOptions o;
  o.fibre_lengths_m = {1000.0, 1000.0, 1000.0};
  Ring ring(s, config_at_mbit(16), config_at_mbit(16), 2, o);
  ring.switch_on_lines();
  for (std::size_t i = 0; i < 3; ++i) ring.serial(i).set_lazy_hops(lazy);
  set_bits(ring.master(), ring.serial(0).fields().repon, true);
  s.run_until(1000 * kBit);
  const Time at = s.now() + 10 * kBit;
  ring.serial(0).rxd().line_burst(
      chip::LineBurst{at, kBit, testing::telegram_bits(0x07, {0x55, 0x55})});
  s.at(at + insert_after_bits * kBit, [&] {
    ring.serial(1).send(ring.serial(1).next_bit_edge(s.now() + 100 * kBit), 0x01,
                        std::vector<std::uint8_t>{1, 0, 0, 0});
  });
  try {
    s.run_until(at + 8000 * kBit);
    return "no error";
  } catch (const std::runtime_error& e) {
    return std::to_string(s.now()) + " " + e.what();
  }
}

TEST(LazyHopsReview, TheCirclingRingErrorIsTheSame) {
  for (Time after : {300, 1000, 2500, 5000}) {
    const std::string a = circling_error(true, after), b = circling_error(false, after);
    dump({a}, "circling " + std::to_string(after));
    EXPECT_NE(a, "no error") << after;  // the ring must really circle, or this proves nothing
    EXPECT_EQ(a, b) << after;
  }
}

}  // namespace
}  // namespace sercon::ring

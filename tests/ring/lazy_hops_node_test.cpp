// Lazy hops at one node (docs/serial-and-ring.md, "Lazy hops"): a chip with its repeater on
// and TxD1 on a fibre is told 20 telegrams ahead, which it passes on lazily, and then one
// thing happens to it while some are still waiting. With lazy hops on and off everything
// must be the same: what leaves on TxD1 and TxD2 (change by change, when it happens), the
// pins TxD1, TxD2, L_ERRN, INT0, INT1 and IDLE at every edge, and registers 0x01, 0x02,
// 0x04, 0x0D read every 60 bit times. Also the two bugs a review found (a node whose TxD
// comes back to its own RxD; a report handler installed while a telegram passes) and a
// ring where every node repeats (the depth guard, docs "Depth guard").
#include <gtest/gtest.h>

#include <algorithm>
#include <stdexcept>
#include <string>
#include <tuple>
#include <vector>

#include "../chip/line_tee.hpp"
#include "repeating_chip.hpp"
#include "ring_bench.hpp"
#include "sercon/chip/chip.hpp"
#include "sercon/chip/serial_unit.hpp"
#include "sercon/chip/serial_unit_fields.hpp"
#include "sercon/chip/serial_unit_receiver.hpp"
#include "sercon/ring/fibre.hpp"
#include "sercon/ring/ring.hpp"
#include "sercon/sim/model_limit.hpp"

namespace sercon::ring {
namespace {

using chip::LineBurst;
using chip::LineCondition;
using sim::Time;
using testing::config_at_mbit;

constexpr Time kBit = 62'500;  // 16 Mbit/s

using testing::AllRepeatRing;
using testing::RepeatingChip;
using testing::set_bits;

std::string event_text(const testing::Recorder::Event& e) {
  std::string s = std::to_string(e.now) + (e.burst ? " burst " : " condition ") +
                  std::string(chip::to_string(e.condition)) + " at " + std::to_string(e.at) +
                  " period " + std::to_string(e.period);
  if (e.burst) s += " bits " + std::to_string(e.bits->size());
  return s;
}

void expect_same(const std::vector<std::string>& lazy, const std::vector<std::string>& full) {
  EXPECT_EQ(lazy.size(), full.size());
  for (std::size_t i = 0; i < std::min(lazy.size(), full.size()); ++i) {
    if (lazy[i] != full[i]) {
      ADD_FAILURE() << "first difference at " << i << "\n lazy: " << lazy[i]
                    << "\n full: " << full[i];
      return;
    }
  }
}

// What happens to the node (register bits: datasheet register table, delta spec 2.3).
enum class Action {
  Rate8Mbit,          // 0x01 ENTSBAUD + SWBAUD: 8 Mbit/s (the waiting bursts at the old rate)
  Rate4Mbit,          // 0x01 ENTSBAUD + SWBAUD16
  Txd2OnThenJoin,     // 0x02 TXOE bit 1, then a listener on TxD2
  JoinThenTxd2On,     // a listener on TxD2, then TXOE bit 1
  Poltxd,             // 0x01 POLTXD flipped
  TestMode,           // 0x02 TMODE2 | TMODE0: a test generator
  SoftReset,          // 0x01 SWRST
  MonitorLimits,      // 0x0D RDISTLIM / FIBBRTIM
  ReponOff,           // 0x01 REPON off
  OwnTelegram,        // the node sends one of its own
  Disconnect,         // TxD1's fibre disconnected
  Ledist,             // 0x02 LEDIST
  Txd2PortMode,       // 0x0B PORTSEL: TxD2 as a port pin
  TxlightOff,         // 0x02 TXLIGHT off
  Txd1Off,            // 0x02 TXOE bit 0 off
  FibreBreak,         // TxD1's fibre broken (it holds the bursts passed through it)
  FibreBreakRestore,  // broken, and restored 20 bits later
  FibreMoved,         // TxD1's fibre connected to another receiver
  FibreBitErrors,     // TxD1's fibre starts flipping bits
};
constexpr int kActions = 19;

// `own_at_bits` >= 0: the node sends a telegram of its own then (before the action).
std::vector<std::string> one_node(Action action, bool lazy, Time when_bits, Time own_at_bits = -1) {
  RepeatingChip node(lazy);
  sim::Scheduler& s = node.s;
  chip::Chip& c = node.c;
  chip::SerialUnit& u = node.u;
  std::vector<std::string> trace;
  testing::Recorder out1(s), out2(s);
  Fibre f(s, 10.0);
  f.connect(out1);
  u.connect_txd(1, f.input());
  for (const chip::Pin p : {chip::Pin::TxD1, chip::Pin::TxD2, chip::Pin::L_ERRN, chip::Pin::INT0,
                            chip::Pin::INT1, chip::Pin::IDLE}) {
    c.pin(p).watch([&trace, &s, p](sim::Level l) {
      trace.push_back(std::to_string(s.now()) + " pin " + std::string(chip::pin_name(p)) + " " +
                      std::to_string(static_cast<int>(l)));
    });
  }
  const Time base = node.idle_then_telegrams(20, 150, 100);
  if (own_at_bits >= 0) {
    s.at(base + own_at_bits * kBit, [&] {
      u.send(u.next_bit_edge(s.now() + 5 * kBit), 0x0A, std::vector<std::uint8_t>{3, 4, 5});
    });
  }
  s.at(base + when_bits * kBit, [&] {
    const auto flip = [&c](std::uint8_t a, std::uint16_t m) {
      c.reg_write(a, static_cast<std::uint16_t>(c.regs().value(a) ^ m));
    };
    switch (action) {
      case Action::Rate8Mbit:
        flip(0x01, static_cast<std::uint16_t>((1u << 10) | (1u << 6)));
        break;
      case Action::Rate4Mbit:
        flip(0x01, static_cast<std::uint16_t>((1u << 10) | (1u << 15)));
        break;
      case Action::Txd2OnThenJoin:
        c.reg_write(0x02, 0x0043);
        u.connect_txd(2, out2);
        break;
      case Action::JoinThenTxd2On:
        u.connect_txd(2, out2);
        c.reg_write(0x02, 0x0043);
        break;
      case Action::Poltxd:
        flip(0x01, 1u << 9);
        break;
      case Action::TestMode:
        flip(0x02, 0x0A00);
        break;
      case Action::SoftReset:
        c.reg_write(0x01, static_cast<std::uint16_t>(c.regs().value(0x01) | 2u));
        break;
      case Action::MonitorLimits:
        c.reg_write(0x0D, 0x0101);
        break;
      case Action::ReponOff:
        flip(0x01, 1u << 3);
        break;
      case Action::OwnTelegram:  // back to back after one of its own still going
        u.send(std::max(u.next_bit_edge(s.now() + 5 * kBit), u.transmit_free_at()), 0x09,
               std::vector<std::uint8_t>{1, 2});
        break;
      case Action::Disconnect:
        u.disconnect_txd(1);
        break;
      case Action::Ledist:
        flip(0x02, 0x0080);
        break;
      case Action::Txd2PortMode:
        c.reg_write(0x0B, 0x0001);
        break;
      case Action::TxlightOff:
        flip(0x02, 0x0040);
        break;
      case Action::Txd1Off:
        flip(0x02, 0x0001);
        break;
      case Action::FibreBreak:
        f.break_now();
        break;
      case Action::FibreBreakRestore:
        f.break_now();
        f.restore_at(s.now() + 20 * kBit);
        break;
      case Action::FibreMoved:
        f.connect(out2);
        break;
      case Action::FibreBitErrors:
        f.set_bit_error_rate(0.01, 7);
        break;
    }
    trace.push_back(std::to_string(s.now()) + " action");
  });
  for (Time k = 1; k < 60; ++k) {
    s.at(base + k * 60 * kBit, [&] {
      trace.push_back(std::to_string(s.now()) + " 0x04 " + std::to_string(c.reg_read(0x04)) +
                      " 0x0D " + std::to_string(c.reg_read(0x0D)));
    });
  }
  s.run_until(base + 3600 * kBit);
  trace.push_back("0x01 " + std::to_string(c.reg_read(0x01)) + " 0x02 " +
                  std::to_string(c.reg_read(0x02)));
  for (const auto& e : out1.events) trace.push_back("TxD1 " + event_text(e));
  for (const auto& e : out2.events) trace.push_back("TxD2 " + event_text(e));
  if (lazy) {
    EXPECT_GT(u.lazy_hops_taken(), 0u);
  }
  return trace;
}

// Before the first burst, inside one, between two, at the start of one, late on.
class LazyHopsOneNode : public ::testing::TestWithParam<std::tuple<int, int>> {};

TEST_P(LazyHopsOneNode, TheSameWhateverHappensWhileBurstsWait) {
  const auto [action, when] = GetParam();
  expect_same(one_node(static_cast<Action>(action), true, when),
              one_node(static_cast<Action>(action), false, when));
}

INSTANTIATE_TEST_SUITE_P(Actions, LazyHopsOneNode,
                         ::testing::Combine(::testing::Range(0, kActions),
                                            ::testing::Values(-5, 30, 75, 149, 160, 1000, 1040)));

// After the 20 telegrams the node sends one of its own, which TxD hands to the fibre and
// keeps out of its line until something looks (TxdOutputs::own_burst, book_own), and then
// each action comes: before the telegram begins, at its start, under it, at and after its
// end, late on.
class LazyHopsOwnTelegram : public ::testing::TestWithParam<std::tuple<int, int>> {};

TEST_P(LazyHopsOwnTelegram, TheSameWhateverHappensAfterIt) {
  const auto [action, after] = GetParam();
  constexpr Time kOwnAt = 3000;  // bits after the first telegram: the last one has passed
  expect_same(one_node(static_cast<Action>(action), true, kOwnAt + 5 + after, kOwnAt),
              one_node(static_cast<Action>(action), false, kOwnAt + 5 + after, kOwnAt));
}

INSTANTIATE_TEST_SUITE_P(Actions, LazyHopsOwnTelegram,
                         ::testing::Combine(::testing::Range(0, kActions),
                                            ::testing::Values(-4, -1, 0, 3, 20, 48, 56, 70, 200)));

// An own telegram while RxD carries idle fill at another rate (4 Mbit/s): TxD hands the
// telegram to the fibre unbooked (TxdOutputs::own_burst), and the repeated fill after it
// is a change the line takes only after the telegram. The same with lazy hops off.
std::vector<std::string> own_over_other_rate(bool lazy) {
  RepeatingChip node(lazy);
  sim::Scheduler& s = node.s;
  testing::Recorder out(s);
  Fibre f(s, 10.0);
  node.repeat_into(f, out);
  s.run_until(1000 * kBit);
  node.u.rxd().line_condition(s.now(), LineCondition::Idle, 4 * kBit);
  s.run_until(s.now() + 100 * kBit);
  node.u.send(node.u.next_bit_edge(s.now() + 5 * kBit), 0x0A, std::vector<std::uint8_t>{3, 4});
  s.run_until(s.now() + 30 * kBit);
  f.break_now();  // the fibre reads its history
  f.restore_at(s.now() + 10 * kBit);
  s.run_until(s.now() + 400 * kBit);
  std::vector<std::string> trace;
  for (const auto& e : out.events) trace.push_back(event_text(e));
  return trace;
}

TEST(LazyHops, AnOwnTelegramOverFillAtAnotherRateIsTheSame) {
  const std::vector<std::string> lazy = own_over_other_rate(true);
  expect_same(lazy, own_over_other_rate(false));
  EXPECT_GE(lazy.size(), 3u);  // the fill, the telegram, the fill after it
}

// An own telegram sent as the last of three lazy bursts leaves or after: mostly it settles
// first and TxD hands the telegram on unbooked (SerialRepeater::own_settled). On a fibre
// of no delay the burst may still be leaving TxD as the telegram begins, which the full path
// drops from TxD's line (line_burst). The same with lazy hops off: what leaves on TxD1 and
// the pins TxD1 and IDLE.
std::vector<std::string> own_after_settle(double fibre_m, Time own_at_bits, bool lazy) {
  RepeatingChip node(lazy);
  sim::Scheduler& s = node.s;
  chip::SerialUnit& u = node.u;
  std::vector<std::string> trace;
  testing::Recorder out(s);
  Fibre f(s, fibre_m);
  node.repeat_into(f, out);
  for (const chip::Pin p : {chip::Pin::TxD1, chip::Pin::IDLE}) {
    node.c.pin(p).watch([&trace, &s, p](sim::Level l) {
      trace.push_back(std::to_string(s.now()) + " pin " + std::string(chip::pin_name(p)) + " " +
                      std::to_string(static_cast<int>(l)));
    });
  }
  const Time base = node.idle_then_telegrams(3, 150, 100);
  s.at(base + own_at_bits * kBit / 4, [&] {
    u.send(u.next_bit_edge(s.now()), 0x0A, std::vector<std::uint8_t>{3, 4});
  });
  s.run_until(base + 1000 * kBit);
  for (const auto& e : out.events) trace.push_back("TxD1 " + event_text(e));
  return trace;
}

TEST(LazyHops, AnOwnTelegramAfterASettledBurstIsTheSame) {
  for (const double m : {0.0, 10.0}) {
    for (Time quarter = 4 * 300; quarter < 4 * 420; ++quarter) {
      SCOPED_TRACE(std::to_string(m) + " m, at " + std::to_string(quarter) + "/4 bits");
      expect_same(own_after_settle(m, quarter, true), own_after_settle(m, quarter, false));
    }
  }
}

// A node whose TxD1 fibre comes back to its own RxD, repeater on (a ring of one). A burst
// that takes the full path reaches the same RxD again from inside the fibre's history;
// that lap is lazy and books into the same history. It used to read the burst after the
// history had moved it (review). `k` changes before vary how full the history is.
std::vector<std::string> loop_of_one(int k, bool lazy) {
  RepeatingChip node(lazy);
  sim::Scheduler& s = node.s;
  chip::Chip& c = node.c;
  chip::SerialUnit& u = node.u;
  Fibre f(s, 10000.0);  // 50 µs = 800 bits: a lap is longer than the telegram
  u.connect_txd(1, f.input());
  f.connect(u.rxd());
  std::vector<std::string> trace;
  c.pin(chip::Pin::RECACTN).watch([&trace, &s](sim::Level l) {
    trace.push_back(std::to_string(s.now()) + " RECACTN " + std::to_string(static_cast<int>(l)));
  });
  s.run_until(1000 * kBit);
  u.rxd().line_condition(s.now(), LineCondition::Idle, kBit);
  s.run_until(s.now() + 1000 * kBit);
  for (int i = 0; i < k; ++i) {
    u.rxd().line_condition(s.now() + kBit,
                           i % 2 == 0 ? LineCondition::ZeroBits : LineCondition::Idle, kBit);
    s.run_until(s.now() + 1000 * kBit);
  }
  const Time base = s.now() + 10 * kBit;
  u.rxd().line_condition(base + 500 * kBit, LineCondition::Idle, kBit);  // superseded next
  u.rxd().line_burst(LineBurst{base, kBit, testing::telegram_bits(0x07, {0x55, 0x55})});
  s.run_until(s.now() + 2000 * kBit);
  return trace;
}

TEST(LazyHops, ANodeThatHearsItselfPassesItsBurstRoundSafely) {
  for (int k = 0; k <= 14; ++k) {
    SCOPED_TRACE(k);
    expect_same(loop_of_one(k, true), loop_of_one(k, false));
  }
}

// Connecting the far end of that loop while telegrams are on their way tells it what is
// still coming, once (docs/serial-and-ring.md, "Fibre"); it used to walk the history while
// what it told came back into it, and never returned (review).
TEST(LazyHops, ConnectingALoopWhileTelegramsAreOnTheirWayReturns) {
  for (const bool lazy : {true, false}) {
    RepeatingChip node(lazy);
    sim::Scheduler& s = node.s;
    chip::SerialUnit& u = node.u;
    Fibre f(s, 10000.0);
    u.connect_txd(1, f.input());
    const Time base = node.idle_then_telegrams(3, 100, 10);
    s.run_until(base + 310 * kBit);
    f.connect(u.rxd());
    s.run_until(s.now() + 2000 * kBit);
    EXPECT_EQ(s.now(), base + 2310 * kBit);
  }
}

// docs/serial-and-ring.md, "Receiver": a report is made only to a handler there is. An MST
// passes while the unit has a start handler (its telegram processor's) but no telegram
// handler, so the full path marks its detection report done for good; a handler installed
// before the detection must hear the same either way (review).
int told_after_late_handler(bool lazy) {
  RepeatingChip node(lazy);
  sim::Scheduler& s = node.s;
  chip::SerialUnit& u = node.u;
  testing::Recorder sink(s);
  Fibre f(s, 10.0);
  f.connect(sink);
  u.connect_txd(1, f.input());
  s.run_until(1000 * kBit);
  u.rxd().line_condition(s.now(), LineCondition::Idle, kBit);
  s.run_until(s.now() + 100 * kBit);
  u.on_telegram({});
  const Time at = s.now() + 10 * kBit;
  u.rxd().line_burst(LineBurst{at, kBit, testing::telegram_bits(0xFF, {0x00})});  // an MST
  s.run_until(at + 10 * kBit);
  int told = 0;
  u.on_telegram([&told](const chip::ReceivedTelegram&) { ++told; });
  s.run_until(s.now() + 500 * kBit);
  return told;
}

TEST(LazyHops, AHandlerInstalledWhileATelegramPassesHearsTheSame) {
  EXPECT_EQ(told_after_late_handler(true), told_after_late_handler(false));
}

// line.hpp, LineListener::pass_through: a listener passes a burst on unchanged, only later.
// A node keeps its lazy burst's own bits and books them itself later, so a listener that
// hands back other bits or another bit period is refused with a logic_error naming it,
// rather than the node booking what the far end never got; one that keeps them is taken.
//
// A listener that is not a plain link: it passes everything on 1000 ps later, through
// pass_through too. `change_period`: pass_through hands back twice the bit period (which a
// node must refuse).
class PassingLink final : public chip::LineListener {
 public:
  explicit PassingLink(chip::LineListener& far, bool change_period = false)
      : far_(far), change_period_(change_period) {}
  void line_condition(Time at, LineCondition c, Time period) override {
    far_.line_condition(at + 1000, c, period);
  }
  void line_burst(const LineBurst& burst) override { far_.line_burst(later(burst)); }
  bool pass_through(const LineBurst& burst, chip::LineListener*& next, const LineBurst*& out,
                    chip::PassedBursts&) override {
    passed_ = later(burst);
    if (change_period_) passed_.bit_period *= 2;
    next = &far_;
    out = &passed_;
    ++taken;
    return true;
  }
  void book_passed(const LineBurst&) override {}
  int taken = 0;

 private:
  static LineBurst later(const LineBurst& b) {
    return LineBurst{b.start + 1000, b.bit_period, b.bits};
  }
  chip::LineListener& far_;
  bool change_period_;
  LineBurst passed_;
};

TEST(LazyHops, AListenerThatChangesTheBurstItPassesIsRefused) {
  for (const bool change : {false, true}) {
    SCOPED_TRACE(change);
    RepeatingChip node(true);
    testing::Recorder sink(node.s);
    PassingLink link(sink, change);
    node.u.connect_txd(1, link);
    if (!change) {
      node.idle_then_telegrams(3, 150, 100);
      EXPECT_GT(node.u.receiver().lazy_hops_taken(), 0u);
      EXPECT_GT(link.taken, 0);
      continue;
    }
    try {
      node.idle_then_telegrams(3, 150, 100);
      ADD_FAILURE() << "a changed burst was taken";
    } catch (const std::logic_error& e) {
      EXPECT_NE(std::string(e.what()).find("pass_through changed the burst"), std::string::npos)
          << e.what();
    }
  }
}

// A lazy hop asks TxD's lone follower through the plain link the receiver keeps a copy of
// (TxdOutputs::mirror_lone_link): once TxD1's fibre is replaced by a listener that is not a
// plain link, bursts coming after go to that listener, and back to a fibre when one is
// connected again; the same with lazy hops off.
std::vector<std::string> follower_replaced(bool lazy) {
  RepeatingChip node(lazy);
  sim::Scheduler& s = node.s;
  testing::Recorder out1(s), out2(s), out3(s);
  Fibre f(s, 10.0), g(s, 10.0);
  f.connect(out1);
  g.connect(out3);
  PassingLink link(out2);
  node.u.connect_txd(1, f.input());
  node.idle_then_telegrams(3, 150, 100);
  s.run_until(s.now() + 800 * kBit);  // after the three
  const auto telegrams = [&](int n) {
    Time at = s.now() + 100 * kBit;
    for (int i = 0; i < n; ++i, at += 150 * kBit) {
      s.run_until(at - 50 * kBit);  // each announced shortly before it comes
      node.u.rxd().line_burst(LineBurst{at, kBit, testing::telegram_bits(0x07, {0x55, 0x55})});
    }
    s.run_until(at + 300 * kBit);
  };
  node.u.connect_txd(1, link);
  telegrams(3);
  node.u.connect_txd(1, g.input());
  telegrams(3);
  if (lazy) {
    EXPECT_GT(link.taken, 0);
    EXPECT_GT(node.u.lazy_hops_taken(), 6u);
  }
  std::vector<std::string> trace;
  for (const auto& e : out1.events) trace.push_back("1 " + event_text(e));
  for (const auto& e : out2.events) trace.push_back("2 " + event_text(e));
  for (const auto& e : out3.events) trace.push_back("3 " + event_text(e));
  return trace;
}

TEST(LazyHops, BurstsAfterTheFollowerIsReplacedGoToTheNewOne) {
  expect_same(follower_replaced(true), follower_replaced(false));
}

// docs/serial-and-ring.md, "Absorbing": a plan of reports (here the telegram processor's
// interest changed) that wants none of the waiting bursts' reports leaves them lazy; a read
// of the line still absorbs them.
TEST(LazyHops, APlanWantingNoneOfTheirReportsLeavesTheBurstsLazy) {
  RepeatingChip node(true);
  testing::Recorder sink(node.s);
  Fibre f(node.s, 10.0);
  f.connect(sink);
  node.u.connect_txd(1, f.input());
  const Time base = node.idle_then_telegrams(20, 150, 100);
  node.s.run_until(base + 400 * kBit);
  const std::size_t waiting = node.u.receiver().lazy_bursts_waiting();
  ASSERT_GT(waiting, 1u);
  node.u.interest_changed();
  EXPECT_EQ(node.u.receiver().lazy_bursts_waiting(), waiting);
  (void)node.u.receiver().input();
  EXPECT_EQ(node.u.receiver().lazy_bursts_waiting(), 0u);
}

// A ring where every node repeats, the master too: a telegram circles it for good, through
// lazy hops and the depth guard's deferred forwards (docs "Depth guard"); the line at the
// master's RxD is the same either way.
std::vector<std::string> every_node_repeats(bool lazy) {
  AllRepeatRing all(2, lazy);
  sim::Scheduler& s = all.s;
  Ring& ring = all.ring;
  chip::testing::LineTee<testing::Recorder> tap(ring.serial(0).rxd(), s);
  ring.fibre(2).connect(tap);
  s.run_until(1000 * kBit);
  const Time at = s.now() + 10 * kBit;
  ring.serial(0).rxd().line_burst(LineBurst{at, kBit, testing::telegram_bits(0x07, {0x55, 0x55})});
  s.run_until(at + 400'000 * kBit);
  std::vector<std::string> trace;
  for (const auto& e : tap.log.events) trace.push_back(event_text(e));
  return trace;
}

TEST(LazyHops, ARingWhereEveryNodeRepeatsIsTheSame) {
  const std::vector<std::string> lazy = every_node_repeats(true);
  EXPECT_GT(lazy.size(), 1000u);
  expect_same(lazy, every_node_repeats(false));
}

// The same ring, and slave 1 inserts an own telegram: what circles is re-announced at every
// insertion and grows without end in the model (not on the fibre). That is an error naming
// the cause, not a hang (docs/serial-and-ring.md, "Depth guard"; review).
TEST(LazyHops, AnOwnTelegramInARingWhereEveryNodeRepeatsIsAnErrorNotAHang) {
  AllRepeatRing all(2);
  sim::Scheduler& s = all.s;
  Ring& ring = all.ring;
  s.run_until(1000 * kBit);
  const Time at = s.now() + 10 * kBit;
  ring.serial(0).rxd().line_burst(LineBurst{at, kBit, testing::telegram_bits(0x07, {0x55, 0x55})});
  s.at(at + 5000 * kBit, [&] {
    ring.serial(1).send(ring.serial(1).next_bit_edge(s.now() + 100 * kBit), 0x01,
                        std::vector<std::uint8_t>{1, 0, 0, 0});
  });
  try {
    s.run_until(at + 8000 * kBit);
    FAIL() << "no error";
  } catch (const sim::ModelLimit& e) {
    EXPECT_NE(std::string(e.what()).find("every node repeats"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace sercon::ring

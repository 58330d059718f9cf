// Fibre (docs/serial-and-ring.md, "Fibre"): delay = length x ps per metre (default 5 ns/m,
// project decision), each announcement (line.hpp) passed on at once with its time moved by
// the delay and the same bits (the recorders here log each change when it happens at the
// far end), breaks (datasheet Table 1 L_ERRN: "when the receive signal is missing"; facts
// §5 FIBBR "fibre broken / ring open") and restores at any time.
#include "sercon/ring/fibre.hpp"

#include <gtest/gtest.h>

#include <cstddef>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "ring_bench.hpp"

namespace sercon::ring {
namespace {

using chip::LineBurst;
using chip::LineCondition;
using sim::Time;
using testing::Ear;
using testing::Recorder;
using testing::telegram_bits;

const std::vector<std::uint8_t> kData = {0x10, 0x20, 0x30, 0x40};

// Decision (docs "Fibre"): delay = round(length x ps per metre), 5 ns/m by default; a
// negative or non-finite length is refused.
TEST(Fibre, DelayIsLengthTimesDelayPerMetre) {
  sim::Scheduler s;
  EXPECT_EQ(Fibre(s, 12.5).delay(), 62'500);  // 5 ns/m default
  EXPECT_EQ(Fibre(s, 0.0).delay(), 0);
  EXPECT_EQ(Fibre(s, 100.0, 4'900).delay(), 490'000);
  EXPECT_EQ(Fibre(s, 0.0001).delay(), 1);  // rounded to the picosecond
  EXPECT_THROW(Fibre(s, -1.0), std::invalid_argument);
  EXPECT_THROW(Fibre(s, std::numeric_limits<double>::infinity()), std::invalid_argument);
  EXPECT_THROW(Fibre(s, std::numeric_limits<double>::quiet_NaN()), std::invalid_argument);
  EXPECT_THROW(Fibre(s, 1.0, -5), std::invalid_argument);
}

// Line contract: the far end is told when a change happens there (now == at), bursts keep
// their shared bits (no per-hop copy).
TEST(Fibre, DeliversEachChangeAtTheFarEndWhenItHappens) {
  sim::Scheduler s;
  Fibre f(s, 20.0);  // 100 ns
  Recorder far(s);
  f.connect(far);
  const auto bits = telegram_bits(1, kData);
  f.input().line_condition(0, LineCondition::Idle, 62'500);
  f.input().line_burst(LineBurst{1'000'000, 62'500, bits});
  s.run_until(999'999);
  f.input().line_condition(2'000'000, LineCondition::Dark, 0);  // announced ahead
  s.run_until(10'000'000);
  ASSERT_EQ(far.events.size(), 4u);  // the far end's state at connect, then 3 changes
  EXPECT_EQ(far.events[0].condition, LineCondition::Dark);
  EXPECT_EQ(far.events[1].at, 100'000);
  EXPECT_EQ(far.events[1].now, 100'000);
  EXPECT_EQ(far.events[1].condition, LineCondition::Idle);
  EXPECT_TRUE(far.events[2].burst);
  EXPECT_EQ(far.events[2].at, 1'100'000);
  EXPECT_EQ(far.events[2].now, 1'100'000);
  EXPECT_EQ(far.events[2].bits.get(), bits.get());
  EXPECT_EQ(far.events[3].at, 2'100'000);
  EXPECT_EQ(far.events[3].condition, LineCondition::Dark);
}

// Line contract (line.hpp, docs "Per telegram, not per bit"): malformed changes and a
// change before now are refused, the message naming the time. A change announced for an
// earlier time than one before it is no error: the later word wins, the far end never sees
// the overtaken one.
TEST(Fibre, RefusesMalformedChangesOrChangesBeforeNow) {
  sim::Scheduler s;
  Fibre f(s, 1.0);  // 5 ns
  Recorder far(s);
  f.connect(far);
  f.input().line_condition(1000, LineCondition::Idle, 62'500);
  EXPECT_NO_THROW(f.input().line_condition(999, LineCondition::Dark, 0));
  EXPECT_THROW(f.input().line_burst(LineBurst{2000, 62'500, nullptr}), std::invalid_argument);
  EXPECT_THROW(f.input().line_condition(2000, LineCondition::ZeroBits, 0), std::invalid_argument);
  s.run_until(5000);
  try {
    f.input().line_condition(4000, LineCondition::Dark, 0);
    ADD_FAILURE() << "a change before now was taken";
  } catch (const std::invalid_argument& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("4000 ps is before now"), std::string::npos) << what;
  }
  EXPECT_THROW(f.input().line_burst(LineBurst{4999, 62'500, telegram_bits(1, kData)}),
               std::invalid_argument);
  EXPECT_THROW(f.break_at(4000), std::invalid_argument);
  EXPECT_THROW(f.restore_at(4000), std::invalid_argument);
  s.run_until(100'000);
  for (const auto& e : far.events) {
    EXPECT_EQ(e.condition, LineCondition::Dark) << "at " << e.at;  // the Idle was overtaken
    EXPECT_EQ(e.now, e.at);
  }
  ASSERT_EQ(far.events.size(), 2u);  // the far end at connect, then the Dark at 999 + 5 ns
  EXPECT_EQ(far.events[1].at, 999 + 5000);
}

// Lazy hops (line.hpp LineListener::pass_through, docs/serial-and-ring.md "Lazy hops"): a
// whole fibre without bit errors takes a burst by pass_through and hands it back as it
// reaches the far end (same bits and bit period, start moved by the delay), booking it only
// when its history is read (the sender's book_all, before anything else enters). It refuses,
// taking nothing, what line_burst() would refuse, a broken or erring fibre, and a burst of
// a second sender while the first one's bursts wait unbooked.
class Sender final : public chip::PassedBursts {
 public:
  explicit Sender(Fibre& f) : fibre_(f) {}
  void book_all() override {
    ++asked;
    for (const LineBurst& b : passed) fibre_.input().book_passed(b);
    passed.clear();
  }
  std::vector<LineBurst> passed;  // taken by the fibre, not yet booked
  int asked = 0;

 private:
  Fibre& fibre_;
};

TEST(Fibre, PassThroughTakesOnlyWhatItCanPassOnUnchanged) {
  sim::Scheduler s;
  Fibre f(s, 2.0);  // 10 ns
  Recorder far(s);
  f.connect(far);
  Sender first(f), second(f);
  const auto bits = telegram_bits(1, kData);
  chip::LineListener* next = nullptr;
  const LineBurst* out = nullptr;
  const auto pass = [&](const LineBurst& b, Sender& sender) {
    next = nullptr;
    out = nullptr;
    const bool taken = f.input().pass_through(b, next, out, sender);
    if (taken) sender.passed.push_back(b);
    return taken;
  };
  s.run_until(1'000);
  EXPECT_FALSE(pass(LineBurst{2'000, 62'500, nullptr}, first));  // no bits
  EXPECT_FALSE(pass(LineBurst{2'000, 0, bits}, first));          // no bit period
  EXPECT_FALSE(pass(LineBurst{999, 62'500, bits}, first));       // before now
  EXPECT_EQ(next, nullptr);
  ASSERT_TRUE(pass(LineBurst{2'000, 62'500, bits}, first));
  EXPECT_EQ(next, &far);
  ASSERT_NE(out, nullptr);
  EXPECT_EQ(out->start, 12'000);
  EXPECT_EQ(out->bit_period, 62'500);
  EXPECT_EQ(out->bits.get(), bits.get());
  // Another sender while the first one's burst waits: refused, nothing asked of anyone.
  EXPECT_FALSE(pass(LineBurst{3'000'000, 62'500, bits}, second));
  EXPECT_EQ(first.asked, 0);
  // What enters next has the first sender book its bursts before it.
  f.input().line_condition(5'000'000, LineCondition::Dark, 0);
  EXPECT_EQ(first.asked, 1);
  EXPECT_TRUE(first.passed.empty());
  ASSERT_TRUE(pass(LineBurst{6'000'000, 62'500, bits}, second));  // booked: free again
  f.input().line_condition(7'000'000, LineCondition::Dark, 0);
  EXPECT_EQ(second.asked, 1);
  f.set_bit_error_rate(0.5, 1);
  EXPECT_FALSE(pass(LineBurst{8'000'000, 62'500, bits}, first));  // errors: the full path
  f.set_bit_error_rate(0.0, 1);
  f.break_at(9'000'000);
  s.run_until(9'000'000);
  EXPECT_FALSE(pass(LineBurst{9'500'000, 62'500, bits}, first));  // broken
  f.restore_at(9'600'000);
  s.run_until(9'600'000);
  EXPECT_TRUE(pass(LineBurst{9'700'000, 62'500, bits}, first));
}

// Docs "Fibre": a fibre schedules nothing; each announcement goes to the far end at once
// (line.hpp "The later word wins"). A Dark announced after a telegram, for a time inside
// it, cuts it there at the far end; a telegram overtaken before it starts never arrives.
TEST(Fibre, ALaterAnnouncementSupersedesWhatIsOnItsWay) {
  sim::Scheduler s;
  Fibre f(s, 20.0);  // 100 ns
  struct Raw final : chip::LineListener {
    void line_condition(Time, LineCondition, Time) override { ++calls; }
    void line_burst(const LineBurst&) override { ++calls; }
    int calls = 0;
  } raw;
  f.connect(raw);
  const int at_connect = raw.calls;
  const auto bits = telegram_bits(1, kData);
  const Time len = static_cast<Time>(bits->size()) * 62'500;
  f.input().line_condition(0, LineCondition::Idle, 62'500);
  f.input().line_burst(LineBurst{1'000'000, 62'500, bits});
  EXPECT_EQ(raw.calls, at_connect + 2);  // passed on within the calls, nothing scheduled
  EXPECT_EQ(s.pending_count(), 0u);

  Fibre g(s, 20.0);
  Recorder far(s);
  g.connect(far);
  g.input().line_condition(0, LineCondition::Idle, 62'500);
  g.input().line_burst(LineBurst{1'000'000, 62'500, bits});
  g.input().line_condition(1'000'000 + len / 2, LineCondition::Dark, 0);  // cuts it
  g.input().line_burst(LineBurst{9'000'000, 62'500, bits});
  g.input().line_condition(8'000'000, LineCondition::Idle, 62'500);  // overtakes it
  s.run_until(20'000'000);
  ASSERT_EQ(far.events.size(), 5u);
  EXPECT_EQ(far.events[1].at, 100'000);
  EXPECT_EQ(far.events[1].condition, LineCondition::Idle);
  EXPECT_TRUE(far.events[2].burst);
  EXPECT_EQ(far.events[2].at, 1'100'000);
  EXPECT_EQ(far.events[2].bits.get(), bits.get());
  EXPECT_FALSE(far.events[3].burst);
  EXPECT_EQ(far.events[3].condition, LineCondition::Dark);
  EXPECT_EQ(far.events[3].at, 1'100'000 + len / 2);
  EXPECT_FALSE(far.events[4].burst);
  EXPECT_EQ(far.events[4].condition, LineCondition::Idle);
  EXPECT_EQ(far.events[4].at, 8'100'000);
  for (const auto& e : far.events) EXPECT_EQ(e.now, e.at);
}

// Docs "Fibre", break / restore: the break darkens the far end and takes back what was on
// its way; the restore gives the present condition at once and then what is still on its
// way (it entered before the restore and arrives after it), also what entered while the
// fibre was broken. A 4 km fibre (20 us) holds whole telegrams: one entered before the
// break, one entered while broken; the fibre is restored before either arrives, and both
// arrive whole at their exact times.
TEST(Fibre, RestoreRedeliversWhatIsStillOnItsWay) {
  sim::Scheduler s;
  chip::Chip rx(s, chip::ChipConfig{});
  Ear ear(rx);
  auto& unit = *rx.unit<chip::SerialUnit>();
  const Time t = unit.bit_period();
  Fibre to_chip(s, 4000.0);
  Fibre to_recorder(s, 4000.0);
  const Time d = to_chip.delay();
  ASSERT_EQ(d, 20'000'000);
  Recorder far(s);
  to_chip.connect(unit.rxd());
  to_recorder.connect(far);
  const auto both = [&](auto&& what) {
    what(to_chip);
    what(to_recorder);
  };
  both([&](Fibre& f) { f.input().line_condition(0, LineCondition::Idle, t); });
  const auto bits = telegram_bits(0x42, kData);
  const Time len = static_cast<Time>(bits->size()) * t;
  const Time in1 = 1000 * t;
  const Time broken = in1 + d / 4, restored = in1 + 3 * d / 4;
  const Time in2 = in1 + len + 30 * t;  // enters while broken
  ASSERT_GT(in2, broken);
  ASSERT_LT(in2, restored);
  s.run_until(in1);
  both([&](Fibre& f) {
    f.input().line_burst(LineBurst{in1, t, bits});
    f.break_at(broken);
    f.restore_at(restored);
  });
  s.run_until(in2);
  EXPECT_TRUE(to_chip.broken());
  both([&](Fibre& f) { f.input().line_burst(LineBurst{in2, t, bits}); });
  s.run_until(in2 + d + len + 200 * t);
  EXPECT_FALSE(to_chip.broken());
  ASSERT_EQ(ear.heard.size(), 2u);
  for (std::size_t i = 0; i < 2; ++i) {
    const Time arrival = (i == 0 ? in1 : in2) + d;
    EXPECT_TRUE(ear.heard[i].frame.ok()) << i;
    EXPECT_EQ(ear.heard[i].start, arrival) << i;
    EXPECT_EQ(ear.heard[i].end, arrival + len) << i;
  }
  // The line as the far end had it: Dark (connect), Idle, Dark at the break, Idle at the
  // restore, then the two telegrams at their times.
  std::vector<std::pair<Time, bool>> changes;
  for (const auto& e : far.events) {
    EXPECT_EQ(e.now, e.at);
    changes.emplace_back(e.at, e.burst);
  }
  const std::vector<std::pair<Time, bool>> expected = {
      {0, false}, {d, false}, {broken, false}, {restored, false}, {in1 + d, true}, {in2 + d, true}};
  EXPECT_EQ(changes, expected);
  EXPECT_EQ(far.events[2].condition, LineCondition::Dark);
  EXPECT_EQ(far.events[3].condition, LineCondition::Idle);
}

// A break in the middle of a telegram cuts it at the break instant: the receiver decodes an
// aborted telegram ending there; with no edges FIBBR rises FIBBRTIM (255) bit times later
// and INT_FIBBR latches. Restored, the signal returns and FIBBR clears.
TEST(Fibre, BreakMidTelegramCutsItAndRaisesFibbrAndRestoreClearsIt) {
  sim::Scheduler s;
  chip::Chip rx(s, chip::ChipConfig{});
  Ear ear(rx);
  auto& unit = *rx.unit<chip::SerialUnit>();
  const Time t = unit.bit_period();
  Fibre f(s, 10.0);  // 50 ns
  f.connect(unit.rxd());
  f.input().line_condition(0, LineCondition::Idle, t);
  const auto bits = telegram_bits(0x42, kData);
  const Time start = 1000 * t;
  s.run_until(start);
  f.input().line_burst(LineBurst{start, t, bits});
  const Time cut = start + f.delay() + 30 * t + 1234;
  f.break_at(cut);
  s.run_until(cut + 254 * t);
  ASSERT_EQ(ear.heard.size(), 1u);
  EXPECT_EQ(ear.heard[0].frame.error, wire::FrameError::Abort);
  EXPECT_EQ(ear.heard[0].start, start + f.delay());
  EXPECT_EQ(ear.heard[0].end, cut);
  EXPECT_FALSE(rx.reg_read(0x02) & (1u << 13));
  s.run_until(cut + 255 * t);
  EXPECT_TRUE(rx.reg_read(0x02) & (1u << 13));  // FIBBR
  EXPECT_TRUE(rx.reg_read(0x04) & (1u << 1));   // INT_FIBBR
  // Telegrams sent while broken are lost.
  f.input().line_burst(LineBurst{s.now(), t, bits});
  s.run_until(s.now() + 1000 * t);
  EXPECT_EQ(ear.heard.size(), 1u);
  f.restore_at(s.now() + 10 * t);
  s.run_until(s.now() + 10 * t);
  EXPECT_FALSE(rx.reg_read(0x02) & (1u << 13));
  f.input().line_burst(LineBurst{s.now(), t, bits});
  s.run_until(s.now() + 1000 * t);
  ASSERT_EQ(ear.heard.size(), 2u);
  EXPECT_TRUE(ear.heard[1].frame.ok());
}

// Restored while a telegram passes: the far end gets the rest of it as idle fill (a
// fragment without its opening flag decodes to nothing).
TEST(Fibre, RestoredMidTelegramTheFarEndSeesIdle) {
  sim::Scheduler s;
  Fibre f(s, 0.0);
  Recorder far(s);
  f.connect(far);
  f.break_now();
  EXPECT_TRUE(f.broken());
  f.input().line_burst(LineBurst{0, 62'500, telegram_bits(1, kData)});
  s.run_until(10 * 62'500);
  f.restore();
  EXPECT_FALSE(f.broken());
  ASSERT_FALSE(far.events.empty());
  EXPECT_FALSE(far.events.back().burst);
  EXPECT_EQ(far.events.back().condition, LineCondition::Idle);
  EXPECT_EQ(far.events.back().period, 62'500);
  EXPECT_EQ(far.events.back().at, 10 * 62'500);
}

// Datasheet Table 1 L_ERRN: "goes low ... when the receive signal is missing". A receiver
// whose fibre is taken away (disconnect(), or the fibre connected to another receiver) sees
// Dark from that moment, as after a break, and raises FIBBR (review wt-a4).
enum class TakeAway { Break, Disconnect, ConnectElsewhere };
bool fibbr_after(TakeAway how) {
  sim::Scheduler s;
  chip::Chip rx(s, chip::ChipConfig{});
  chip::Chip other(s, chip::ChipConfig{});
  auto& unit = *rx.unit<chip::SerialUnit>();
  const Time t = unit.bit_period();
  Fibre f(s, 1.0);
  f.connect(unit.rxd());
  f.input().line_condition(0, LineCondition::Idle, t);
  s.run_until(1000 * t);
  EXPECT_FALSE(rx.reg_read(0x02) & (1u << 13));  // FIBBR clear while the fill arrives
  switch (how) {
    case TakeAway::Break:
      f.break_now();
      break;
    case TakeAway::Disconnect:
      f.disconnect();
      break;
    case TakeAway::ConnectElsewhere:
      f.connect(other.unit<chip::SerialUnit>()->rxd());
      break;
  }
  s.run_until(2000 * t);  // FIBBRTIM resets to 255 bit times
  return (rx.reg_read(0x02) & (1u << 13)) != 0;
}

TEST(Fibre, AReceiverWhoseFibreIsTakenAwaySeesTheSignalMissing) {
  EXPECT_TRUE(fibbr_after(TakeAway::Break));  // control
  EXPECT_TRUE(fibbr_after(TakeAway::Disconnect)) << "disconnect(): RxD keeps the idle fill";
  EXPECT_TRUE(fibbr_after(TakeAway::ConnectElsewhere))
      << "connect() while connected: the first receiver keeps the idle fill";
}

// The receiver left is told Dark at the moment it is left; connecting the same receiver
// again is no leaving.
TEST(Fibre, TheReceiverLeftIsToldDarkNow) {
  sim::Scheduler s;
  Fibre f(s, 0.0);
  Recorder a(s);
  Recorder b(s);
  f.connect(a);
  f.input().line_condition(0, LineCondition::Idle, 62'500);
  s.run_until(100'000);
  f.connect(a);  // the same receiver: told the present condition again, not Dark
  ASSERT_FALSE(a.events.empty());
  EXPECT_EQ(a.events.back().condition, LineCondition::Idle);
  f.connect(b);
  EXPECT_EQ(a.events.back().condition, LineCondition::Dark);
  EXPECT_EQ(a.events.back().at, 100'000);
  EXPECT_EQ(b.events.back().condition, LineCondition::Idle);
  s.run_until(200'000);
  f.disconnect();
  EXPECT_EQ(b.events.back().condition, LineCondition::Dark);
  EXPECT_EQ(b.events.back().at, 200'000);
  const std::size_t after = b.events.size();
  f.disconnect();  // nothing left to tell
  EXPECT_EQ(b.events.size(), after);
}

}  // namespace
}  // namespace sercon::ring

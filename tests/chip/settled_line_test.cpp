// chip::SettledLine (settled_line.hpp; docs/serial-and-ring.md, "Per telegram, not per
// bit": "A listener written for "now" ... sits behind chip::SettledLine, which passes each
// change on at its time with one event per change"). Line contract (line.hpp): a call's time
// is never before now; the later word wins: a call supersedes everything announced before
// for its time and later, and cuts a telegram under way at its time.
#include "sercon/chip/settled_line.hpp"

#include <gtest/gtest.h>

#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "sercon/wire/encoder.hpp"

namespace sercon::chip {
namespace {

using sim::Time;

constexpr Time kBit = 62'500;

chip::SharedBits bits_of(std::uint8_t address) {
  wire::LineEncoder encoder(true);
  const std::vector<std::uint8_t> data = {0x01, 0x02};
  encoder.telegram(address, data);
  return chip::share_bits(encoder.take());
}

// What the target hears: each call with the scheduler's time.
struct Heard {
  Time now, at;
  bool burst;
  LineCondition condition;
  Time period;
  const wire::LineBits* bits;
  bool operator==(const Heard&) const = default;
};

class Log final : public LineListener {
 public:
  explicit Log(const sim::Scheduler& s) : s_(s) {}
  void line_condition(Time at, LineCondition c, Time period) override {
    heard.push_back({s_.now(), at, false, c, period, nullptr});
  }
  void line_burst(const LineBurst& b) override {
    heard.push_back({s_.now(), b.start, true, LineCondition::Idle, b.bit_period, b.bits.get()});
  }
  std::vector<Heard> heard;

 private:
  const sim::Scheduler& s_;
};

// Each announced change reaches the target at its own time (now == at), in time order, with
// what was announced (period, the same bits object); one scheduled event per change; a
// change for now goes on at once.
TEST(SettledLine, PassesEachChangeOnAtItsTime) {
  sim::Scheduler s;
  Log log(s);
  SettledLine line(s, log);
  const auto bits = bits_of(0x11);
  line.line_condition(0, LineCondition::Idle, kBit);  // now: at once
  ASSERT_EQ(log.heard.size(), 1u);
  line.line_burst(LineBurst{1'000'000, kBit, bits});
  const Time end = 1'000'000 + static_cast<Time>(bits->size()) * kBit;
  line.line_condition(end + 7, LineCondition::Light, 0);
  line.line_condition(end + 1'000'000, LineCondition::Dark, 0);
  EXPECT_EQ(s.pending_count(), 3u);
  EXPECT_EQ(log.heard.size(), 1u);  // nothing before its time
  s.run_until(999'999);
  EXPECT_EQ(log.heard.size(), 1u);
  s.run_until(10'000'000);
  const std::vector<Heard> expected = {
      {0, 0, false, LineCondition::Idle, kBit, nullptr},
      {1'000'000, 1'000'000, true, LineCondition::Idle, kBit, bits.get()},
      {end + 7, end + 7, false, LineCondition::Light, 0, nullptr},
      {end + 1'000'000, end + 1'000'000, false, LineCondition::Dark, 0, nullptr},
  };
  EXPECT_EQ(log.heard, expected);
  EXPECT_EQ(s.pending_count(), 0u);
}

// The later word wins: an announcement for an earlier time drops every change announced for
// its time and later (their events too); one for the same time replaces it; one inside a
// telegram already passed on comes at its time, which cuts the telegram for the target.
TEST(SettledLine, ALaterAnnouncementForAnEarlierTimeDropsTheOvertakenOnes) {
  sim::Scheduler s;
  Log log(s);
  SettledLine line(s, log);
  const auto first = bits_of(0x01), second = bits_of(0x02), third = bits_of(0x03);
  line.line_condition(100, LineCondition::Idle, kBit);
  line.line_burst(LineBurst{1'000'000, kBit, first});
  line.line_condition(9'000'000, LineCondition::Dark, 0);
  line.line_condition(500'000, LineCondition::Light, 0);  // overtakes the burst and the Dark
  EXPECT_EQ(s.pending_count(), 2u);
  line.line_burst(LineBurst{2'000'000, kBit, second});
  line.line_burst(LineBurst{2'000'000, kBit, third});  // same time: replaces it
  s.run_until(2'000'000 + 10 * kBit);
  line.line_condition(2'000'000 + 20 * kBit, LineCondition::Dark, 0);  // inside the third
  s.run_until(20'000'000);
  const std::vector<Heard> expected = {
      {100, 100, false, LineCondition::Idle, kBit, nullptr},
      {500'000, 500'000, false, LineCondition::Light, 0, nullptr},
      {2'000'000, 2'000'000, true, LineCondition::Idle, kBit, third.get()},
      {2'000'000 + 20 * kBit, 2'000'000 + 20 * kBit, false, LineCondition::Dark, 0, nullptr},
  };
  EXPECT_EQ(log.heard, expected);
  EXPECT_EQ(s.pending_count(), 0u);
}

// A time before the scheduler's now is std::invalid_argument naming the time; what was
// announced before stands.
TEST(SettledLine, ATimeBeforeNowIsRefused) {
  sim::Scheduler s;
  Log log(s);
  SettledLine line(s, log);
  line.line_condition(5000, LineCondition::Idle, kBit);
  s.run_until(1000);
  for (const bool burst : {false, true}) {
    try {
      if (burst) {
        line.line_burst(LineBurst{999, kBit, bits_of(1)});
      } else {
        line.line_condition(999, LineCondition::Dark, 0);
      }
      ADD_FAILURE() << "a change before now was taken";
    } catch (const std::invalid_argument& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find("999 ps is before now"), std::string::npos) << what;
    }
  }
  s.run_until(10'000);
  const std::vector<Heard> expected = {{5000, 5000, false, LineCondition::Idle, kBit, nullptr}};
  EXPECT_EQ(log.heard, expected);
}

// Gone before its changes are due: their events go with it.
TEST(SettledLine, DestroyedItTakesItsEventsAlong) {
  sim::Scheduler s;
  Log log(s);
  {
    SettledLine line(s, log);
    line.line_condition(5000, LineCondition::Idle, kBit);
    line.line_burst(LineBurst{9000, kBit, bits_of(1)});
  }
  EXPECT_EQ(s.pending_count(), 0u);
  s.run_until(100'000);
  EXPECT_TRUE(log.heard.empty());
}

}  // namespace
}  // namespace sercon::chip

// The scheduler underlies every timing claim of the model; these tests pin the rules
// the chip models rely on (architecture guide: integer picoseconds; brief: determinism).
#include "sercon/sim/scheduler.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <stdexcept>
#include <vector>

namespace sercon::sim {
namespace {

TEST(Scheduler, RunsEventsInTimeOrderAndAdvancesTheClock) {
  Scheduler s;
  std::vector<Time> seen;
  s.at(300, [&] { seen.push_back(s.now()); });
  s.at(100, [&] { seen.push_back(s.now()); });
  s.at(200, [&] { seen.push_back(s.now()); });
  s.run_until(250);
  EXPECT_EQ(seen, (std::vector<Time>{100, 200}));
  EXPECT_EQ(s.now(), 250);
  s.run_until(1000);
  EXPECT_EQ(seen, (std::vector<Time>{100, 200, 300}));
  EXPECT_EQ(s.now(), 1000);
}

TEST(Scheduler, SameTimeEventsRunInSchedulingOrder) {
  Scheduler s;
  std::vector<int> order;
  for (int i = 0; i < 5; ++i) s.at(42, [&order, i] { order.push_back(i); });
  s.run_until(42);
  EXPECT_EQ(order, (std::vector<int>{0, 1, 2, 3, 4}));
}

TEST(Scheduler, EventsScheduledByEventsAtTheSameTimeRunBeforeTheClockMoves) {
  Scheduler s;
  std::vector<int> order;
  s.at(10, [&] {
    order.push_back(1);
    s.after(0, [&] { order.push_back(2); });
  });
  s.at(11, [&] { order.push_back(3); });
  s.run_until(20);
  EXPECT_EQ(order, (std::vector<int>{1, 2, 3}));
}

TEST(Scheduler, CancelledEventsNeverRun) {
  Scheduler s;
  bool ran = false;
  auto id = s.at(5, [&] { ran = true; });
  EXPECT_TRUE(s.pending(id));
  EXPECT_TRUE(s.cancel(id));
  EXPECT_FALSE(s.cancel(id));
  s.run_until(10);
  EXPECT_FALSE(ran);
  EXPECT_EQ(s.pending_count(), 0u);
}

TEST(Scheduler, RefusesThePast) {
  Scheduler s;
  s.run_until(100);
  EXPECT_THROW(s.at(99, [] {}), std::invalid_argument);
  EXPECT_THROW(s.run_until(50), std::invalid_argument);
  EXPECT_NO_THROW(s.at(100, [] {}));
}

TEST(Scheduler, StepRunsOneEventAndSkipsCancelledOnes) {
  Scheduler s;
  int count = 0;
  auto first = s.at(1, [&] { ++count; });
  s.at(2, [&] { ++count; });
  s.cancel(first);
  EXPECT_TRUE(s.step());
  EXPECT_EQ(count, 1);
  EXPECT_EQ(s.now(), 2);
  EXPECT_FALSE(s.step());
}

TEST(Scheduler, NextTimeSkipsCancelledEventsAndRunsNothing) {
  Scheduler s;
  EXPECT_EQ(s.next_time(), std::nullopt);
  auto first = s.at(5, [] {});
  s.at(9, [] {});
  EXPECT_EQ(s.next_time(), 5);
  s.cancel(first);
  EXPECT_EQ(s.next_time(), 9);
  EXPECT_EQ(s.now(), 0);
  EXPECT_EQ(s.pending_count(), 1u);
}

// docs/architecture.md, "Determinism": events run in time order, and events at the same
// picosecond in the order they were scheduled, however many are pending and whatever was
// cancelled or scheduled while others ran (the queue moves entries both ways and reuses
// the room of those that ran).
TEST(Scheduler, ManyInterleavedEventsRunInTimeThenSchedulingOrder) {
  Scheduler s;
  struct Planned {
    Time when;
    int serial;
  };
  std::vector<Planned> planned;  // in scheduling order
  std::vector<int> cancelled;
  std::vector<Scheduler::EventId> ids;
  std::vector<Planned> seen;
  std::uint32_t random = 12345;
  auto next_random = [&random](std::uint32_t range) {
    random = random * 1103515245u + 12345u;
    return (random >> 8) % range;
  };
  int serial = 0;
  auto schedule = [&](Time when) {
    const int mine = serial++;
    planned.push_back({when, mine});
    ids.push_back(s.at(when, [&s, &seen, mine] { seen.push_back({s.now(), mine}); }));
  };
  for (int round = 0; round < 200; ++round) {
    const std::uint32_t count = next_random(12);
    for (std::uint32_t i = 0; i < count; ++i) {
      schedule(s.now() + static_cast<Time>(next_random(40)));  // many share a time
    }
    if (!ids.empty() && next_random(3) == 0) {
      const std::size_t victim = next_random(static_cast<std::uint32_t>(ids.size()));
      if (s.cancel(ids[victim])) cancelled.push_back(planned[victim].serial);
    }
    s.run_until(s.now() + static_cast<Time>(next_random(15)));
  }
  s.run_until(s.now() + 100);
  std::vector<Planned> expected;
  for (const Planned& p : planned) {
    if (std::find(cancelled.begin(), cancelled.end(), p.serial) == cancelled.end()) {
      expected.push_back(p);
    }
  }
  std::stable_sort(expected.begin(), expected.end(),
                   [](const Planned& a, const Planned& b) { return a.when < b.when; });
  ASSERT_EQ(seen.size(), expected.size());
  for (std::size_t i = 0; i < seen.size(); ++i) {
    EXPECT_EQ(seen[i].when, expected[i].when) << "event " << i;
    EXPECT_EQ(seen[i].serial, expected[i].serial) << "event " << i;
  }
  EXPECT_EQ(s.pending_count(), 0u);
}

// docs/timing.md, "Cycle-time events" (moved if MCLKDIV changes) and docs/architecture.md,
// "Determinism": a moved event keeps its id and runs after the events already due at its
// new time, as if scheduled then; when() follows it and is empty once it ran.
TEST(Scheduler, MovedEventKeepsItsIdAndGoesAfterThoseAtItsNewTime) {
  Scheduler s;
  std::vector<char> order;
  const auto moved = s.at(10, [&] { order.push_back('m'); });
  s.at(30, [&] { order.push_back('a'); });
  s.at(20, [&] { order.push_back('b'); });
  EXPECT_EQ(s.when(moved), 10);
  EXPECT_TRUE(s.move(moved, 30));
  EXPECT_EQ(s.when(moved), 30);
  s.at(30, [&] { order.push_back('c'); });
  EXPECT_THROW(s.move(moved, -1), std::invalid_argument);
  s.run_until(100);
  EXPECT_EQ(order, (std::vector<char>{'b', 'a', 'm', 'c'}));
  EXPECT_EQ(s.when(moved), std::nullopt);
  EXPECT_FALSE(s.move(moved, 200));
}

TEST(Time, BitAndClockPeriodsAreExactPicoseconds) {
  EXPECT_EQ(period_of_hz(16'000'000), 62'500);  // 16 Mbit/s bit: 62.5 ns
  EXPECT_EQ(period_of_hz(64'000'000), 15'625);  // 64 MHz MCLK: 15.625 ns
  EXPECT_EQ(period_of_hz(2'000'000), 500 * kNanosecond);
}

}  // namespace
}  // namespace sercon::sim

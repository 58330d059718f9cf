// The scheduler underlies every timing claim of the model; these tests pin the rules
// the chip models rely on (architecture guide: integer picoseconds; brief: determinism).
#include "sercon/sim/scheduler.hpp"

#include <gtest/gtest.h>

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

TEST(Time, BitAndClockPeriodsAreExactPicoseconds) {
  EXPECT_EQ(period_of_hz(16'000'000), 62'500);  // 16 Mbit/s bit: 62.5 ns
  EXPECT_EQ(period_of_hz(64'000'000), 15'625);  // 64 MHz MCLK: 15.625 ns
  EXPECT_EQ(period_of_hz(2'000'000), 500 * kNanosecond);
}

}  // namespace
}  // namespace sercon::sim

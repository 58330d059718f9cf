#include "sercon/sim/signal.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace sercon::sim {
namespace {

TEST(Signal, WatchersHearChangesOnly) {
  Signal pin("INT0", Level::High);
  std::vector<Level> heard;
  pin.watch([&](Level l) { heard.push_back(l); });
  pin.set(Level::High);  // no change
  pin.set(Level::Low);
  pin.set(Level::HighZ);
  EXPECT_EQ(heard, (std::vector<Level>{Level::Low, Level::HighZ}));
  EXPECT_EQ(pin.name(), "INT0");
}

TEST(Signal, UnwatchedWatchersAreSilent) {
  Signal pin("x");
  int calls = 0;
  auto handle = pin.watch([&](Level) { ++calls; });
  pin.set(true);
  pin.unwatch(handle);
  pin.set(false);
  EXPECT_EQ(calls, 1);
}

// A unit computing a pin on demand (LazyPin) schedules its edges only while the pin is
// watched: watched() must follow every watch and unwatch, a second unwatch included.
TEST(Signal, WatchedWhileAnyWatcherIsLeft) {
  Signal pin("RECACTN");
  EXPECT_FALSE(pin.watched());
  const auto a = pin.watch([](Level) {});
  const auto b = pin.watch([](Level) {});
  EXPECT_TRUE(pin.watched());
  pin.unwatch(a);
  EXPECT_TRUE(pin.watched());
  pin.unwatch(a);  // again: no effect
  EXPECT_TRUE(pin.watched());
  pin.unwatch(b);
  EXPECT_FALSE(pin.watched());
  pin.unwatch(99);  // no such handle: no effect
  EXPECT_FALSE(pin.watched());
}

}  // namespace
}  // namespace sercon::sim

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

}  // namespace
}  // namespace sercon::sim

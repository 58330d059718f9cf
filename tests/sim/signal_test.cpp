#include "sercon/sim/signal.hpp"

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>
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

// signal.hpp: a change made while watchers hear another takes effect at once, and its
// watchers hear it after every watcher of the change being told; changes are heard in the
// order they happened, each with its own level.
TEST(Signal, AChangeMadeByAWatcherIsHeardAfterTheChangeBeingTold) {
  Signal a("a"), b("b");
  std::vector<std::string> heard;
  a.watch([&](Level) {
    heard.push_back("a1");
    b.set(Level::High);
    EXPECT_EQ(b.level(), Level::High);  // in effect at once
    b.set(Level::Low);
    heard.push_back("a1 done");
  });
  a.watch([&](Level) { heard.push_back("a2"); });
  b.watch([&](Level l) { heard.push_back(std::string("b ") + level_char(l)); });
  a.set(Level::High);
  EXPECT_EQ(heard, (std::vector<std::string>{"a1", "a1 done", "a2", "b 1", "b 0"}));
  heard.clear();
  b.set(Level::High);  // not inside a change: heard at once
  EXPECT_EQ(heard, std::vector<std::string>{"b 1"});
}

// A watcher that throws leaves nothing queued: the next change is told as usual.
TEST(Signal, AWatcherThatThrowsLeavesTheNextChangeToldAtOnce) {
  Signal a("a"), b("b");
  int b_heard = 0;
  a.watch([&](Level) {
    b.set(Level::High);
    throw std::runtime_error("watcher failed");
  });
  b.watch([&](Level) { ++b_heard; });
  EXPECT_THROW(a.set(Level::High), std::runtime_error);
  EXPECT_EQ(b_heard, 0);
  b.set(Level::Low);
  EXPECT_EQ(b_heard, 1);
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

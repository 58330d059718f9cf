// The scheduler underlies every timing claim of the model; these tests pin the rules
// the chip models rely on (architecture guide: integer picoseconds; brief: determinism).
#include "sercon/sim/scheduler.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <functional>
#include <optional>
#include <stdexcept>
#include <string>
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

// docs/architecture.md, "Determinism": an event scheduled before others already pending
// (a few places in, where the queue walks to its place, or far in, where it searches)
// runs after every event already due at its time and before the later ones.
TEST(Scheduler, LateComersRunAfterThoseAlreadyDueAtTheirTime) {
  Scheduler s;
  std::vector<int> order;
  struct Tag {
    std::vector<int>* order;
    int value;
  };
  std::vector<Tag> tags;
  tags.reserve(64);
  auto schedule = [&](Time when, int value) {
    tags.push_back({&order, value});
    s.at(
        when,
        [](void* tag) {
          auto* t = static_cast<Tag*>(tag);
          t->order->push_back(t->value);
        },
        &tags.back());
  };
  for (int i = 0; i < 20; ++i) schedule(10 * (i + 1), 10 * (i + 1));
  schedule(20, 21);  // before any has run: no room before the front yet
  schedule(5, 5);
  s.run_until(20);     // four have run: the queue's front has moved
  schedule(40, 41);    // three places in
  schedule(30, 31);    // at the front's time
  schedule(25, 25);    // before everything pending
  schedule(180, 181);  // far in
  schedule(40, 42);    // after the first late-comer at 40
  s.run_until(1000);
  EXPECT_EQ(order,
            (std::vector<int>{5,  10,  20,  21,  25,  30,  31,  40,  41,  42,  50,  60,  70, 80,
                              90, 100, 110, 120, 130, 140, 150, 160, 170, 180, 181, 190, 200}));
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

// Bad input gets a clear error: an event with no action would otherwise be taken for an
// at() event with a callback that was never stored.
TEST(Scheduler, RefusesAnEventWithoutAnAction) {
  Scheduler s;
  EXPECT_THROW(s.at(10, nullptr, nullptr), std::invalid_argument);
  EXPECT_THROW(s.after(10, nullptr, nullptr), std::invalid_argument);
  EXPECT_EQ(s.pending_count(), 0u);
  s.run_until(20);  // nothing half-made is left to run
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
// picosecond in the order they were scheduled (a moved event as if scheduled when moved),
// however many are pending, whatever was cancelled or moved meanwhile, and whether they
// are due soon or hundreds of µs ahead (the queue keeps soon and later events apart).
// Far events wait unsorted and are sorted when they come near (scheduler.hpp): many seeds
// and densities, so a refill meets one run in order, runs to merge, a run wholly earlier,
// and more runs than it merges one by one.
void run_interleaved_events(std::uint32_t seed, std::uint32_t most_per_round) {
  Scheduler s;
  struct Event {
    Time when;
    int order;  // the scheduling (or moving) order
    Scheduler::EventId id;
    bool cancelled = false;
  };
  std::vector<Event> events;
  std::vector<std::pair<Time, std::size_t>> seen;
  std::uint32_t random = seed;
  auto next_random = [&random](std::uint32_t range) {
    random = random * 1103515245u + 12345u;
    return (random >> 8) % range;
  };
  constexpr Time kUnit = 10 * kMicrosecond;  // offsets up to 400 µs: many share a time
  auto ahead = [&] {                         // a whole number of units from now, some 1 ps early
    const Time when =
        s.now() + static_cast<Time>(next_random(40)) * kUnit - static_cast<Time>(next_random(2));
    return std::max(when, s.now());
  };
  int order = 0;
  for (int round = 0; round < 300; ++round) {
    const std::uint32_t count = next_random(most_per_round);
    for (std::uint32_t i = 0; i < count; ++i) {
      const Time when = ahead();
      const std::size_t k = events.size();
      events.push_back({when, order++, {}});
      events[k].id = s.at(when, [&s, &seen, k] { seen.emplace_back(s.now(), k); });
    }
    if (events.empty()) continue;
    Event& e = events[next_random(static_cast<std::uint32_t>(events.size()))];
    switch (next_random(3)) {
      case 0:
        if (s.cancel(e.id)) e.cancelled = true;
        break;
      case 1: {
        const Time when = ahead();
        if (s.move(e.id, when)) {
          e.when = when;
          e.order = order++;
        }
        break;
      }
      default:
        break;
    }
    s.run_until(s.now() + static_cast<Time>(next_random(15)) * kUnit);
  }
  s.run_until(s.now() + 100 * kUnit);
  std::vector<std::size_t> expected;
  for (std::size_t k = 0; k < events.size(); ++k) {
    if (!events[k].cancelled) expected.push_back(k);
  }
  std::sort(expected.begin(), expected.end(), [&events](std::size_t a, std::size_t b) {
    const Event& x = events[a];
    const Event& y = events[b];
    return x.when != y.when ? x.when < y.when : x.order < y.order;
  });
  ASSERT_EQ(seen.size(), expected.size()) << "seed " << seed;
  for (std::size_t i = 0; i < seen.size(); ++i) {
    ASSERT_EQ(seen[i].second, expected[i]) << "seed " << seed << ", event " << i;
    ASSERT_EQ(seen[i].first, events[expected[i]].when) << "seed " << seed << ", event " << i;
  }
  EXPECT_EQ(s.pending_count(), 0u);
}

TEST(Scheduler, ManyInterleavedEventsRunInTimeThenSchedulingOrder) {
  for (std::uint32_t seed = 1; seed <= 60; ++seed) {
    run_interleaved_events(seed * 12345u, 12);
    run_interleaved_events(seed * 7919u, 40);
  }
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

// The same rule when the moved event's slot last held a cancelled event of the same time:
// the cancelled one's queue entry is still there, and must not be the one taken out (the
// event ran at its old time and its id read as no longer pending). A chip gets there when
// MCLKDIV is written while a cancelled and a new cycle-time event share their time.
TEST(Scheduler, MovingAnEventInACancelledOnesSlotMovesThatEvent) {
  Scheduler s;
  Time ran = -1;
  const auto cancelled = s.at(100, [] {});
  s.cancel(cancelled);
  const auto moved = s.at(100, [&] { ran = s.now(); });
  EXPECT_TRUE(s.move(moved, 200));
  s.run_until(150);
  EXPECT_EQ(ran, -1);
  EXPECT_EQ(s.when(moved), 200);
  s.run_until(1000);
  EXPECT_EQ(ran, 200);
}

// An owned slot (a receiver's report event) is queued as at() queues an event: after those
// already due at its time, whether armed from outside or again from its own action; a
// cancelled one never runs; disowned, its slot goes back to the free list.
TEST(Scheduler, OwnedEventsRunWhereAtWouldHavePutThem) {
  Scheduler s;
  std::vector<char> order;
  struct Owner {
    Scheduler* s;
    std::vector<char>* order;
    Scheduler::OwnedSlot slot = 0;
    int again = 2;  // arms itself again this many times, 10 ps on
  } owner{&s, &order};
  owner.slot = s.own(
      [](void* self) {
        auto* o = static_cast<Owner*>(self);
        o->order->push_back('o');
        if (o->again-- > 0) o->s->arm_owned(o->slot, o->s->now() + 10);
      },
      &owner);
  EXPECT_FALSE(s.owned_pending(owner.slot));
  s.at(20, [&] { order.push_back('a'); });
  s.arm_owned(owner.slot, 20);
  EXPECT_TRUE(s.owned_pending(owner.slot));
  s.at(20, [&] { order.push_back('b'); });
  s.at(30, [&] { order.push_back('c'); });  // before the owned one armed again for 30
  s.run_until(35);
  s.at(40, [&] { order.push_back('d'); });  // after the one armed for 40 (at 30)
  s.run_until(100);
  EXPECT_EQ(order, (std::vector<char>{'a', 'o', 'b', 'c', 'o', 'o', 'd'}));
  EXPECT_FALSE(s.owned_pending(owner.slot));
  EXPECT_THROW(s.arm_owned(owner.slot, 50), std::invalid_argument);
  EXPECT_FALSE(s.owned_pending(owner.slot));

  s.arm_owned(owner.slot, 200);
  EXPECT_EQ(s.pending_count(), 1u);
  s.cancel_owned(owner.slot);
  EXPECT_EQ(s.pending_count(), 0u);
  s.run_until(300);
  EXPECT_EQ(order.size(), 7u);

  s.arm_owned(owner.slot, 400);
  s.disown(owner.slot);  // cancelled, and its slot free again: the next at() takes it
  EXPECT_EQ(s.pending_count(), 0u);
  const auto reused = s.at(500, [&] { order.push_back('e'); });
  EXPECT_EQ(reused.slot, owner.slot);
  s.run_until(1000);
  EXPECT_EQ(order.back(), 'e');
  EXPECT_EQ(order.size(), 8u);
}

// An owned slot's rules are checked, not assumed: arming it while it is pending would leave
// owned_pending() reading the wrong way from then on, and moving it while it is not pending
// would look for a queue entry that is not there. A slot given back is taken again by the
// next own(), with its action index, so a scheduler that outlives many owners does not grow.
TEST(Scheduler, OwnedSlotRulesAreCheckedAndGivenBackSlotsAreTakenAgain) {
  Scheduler s;
  int runs = 0;
  const Scheduler::Action count = [](void* n) { ++*static_cast<int*>(n); };
  const Scheduler::OwnedSlot slot = s.own(count, &runs);
  EXPECT_THROW(s.move_owned(slot, 10), std::logic_error);
  s.arm_owned(slot, 10);
  EXPECT_THROW(s.arm_owned(slot, 20), std::logic_error);
  EXPECT_THROW(s.arm_owned_now(slot), std::logic_error);
  EXPECT_THROW(s.arm_owned(slot, 20, count), std::logic_error);
  EXPECT_THROW(s.arm_owned(slot, -1), std::invalid_argument);
  EXPECT_THROW(s.defer_owned(slot, 20, count), std::logic_error);
  EXPECT_TRUE(s.owned_pending(slot));
  s.run_until(10);
  EXPECT_EQ(runs, 1);  // the refused arms left the one event as it was
  EXPECT_FALSE(s.owned_pending(slot));

  s.disown(slot);
  int other_runs = 0;
  const Scheduler::OwnedSlot again = s.own(count, &other_runs);
  EXPECT_EQ(again, slot);
  s.arm_owned(again, 30);
  s.run_until(30);
  EXPECT_EQ(other_runs, 1);
  EXPECT_EQ(runs, 1);
  EXPECT_THROW(s.defer_owned(again, 20, count), std::invalid_argument);
  s.defer_owned(again, 40, count);
  EXPECT_TRUE(s.owned_pending(again));
  EXPECT_EQ(s.pending_count(), 1u);
  EXPECT_THROW(s.defer_owned(again, 50, count), std::logic_error);
  EXPECT_EQ(s.next_time(), std::optional<Time>{40});
  s.run_until(40);
  EXPECT_EQ(other_runs, 2);
  EXPECT_FALSE(s.owned_pending(again));
  // Owners come and go (rings built one after another on one scheduler): one slot serves.
  const Scheduler::OwnedSlot first = s.own(count, &runs);
  s.disown(first);
  for (int i = 0; i < 100; ++i) {
    const Scheduler::OwnedSlot next = s.own(count, &runs);
    EXPECT_EQ(next, first);
    s.disown(next);
  }
}

// The owned-slot twin tests below run one random workload twice, once with the owner's
// event on an owned slot and once through at() / move() / cancel(), and compare what ran:
// the same events at the same times in the same order.
using Seen = std::vector<std::pair<Time, int>>;

// A linear congruential generator: the same draws in both runs of a twin test.
struct Draws {
  std::uint32_t state;
  std::uint32_t next() {
    state = state * 1103515245u + 12345u;
    return state;
  }
  std::uint32_t below(std::uint32_t range) { return (next() >> 8) % range; }
};

// The owner's event, owned or through EventIds. When it runs it may arm itself again:
// later (Later), for now (Now), or later with either of two actions (LaterEitherAction,
// which arms the owned slot with an action per arm).
struct TwinOwner {
  enum class Again { Later, Now, LaterEitherAction, Deferred };
  Scheduler& s;
  Seen& seen;
  Draws& draws;
  bool owned;
  Again again;
  int label = 100000;
  Scheduler::OwnedSlot slot = 0;
  Scheduler::EventId id{};
  bool armed = false;

  TwinOwner(Scheduler& scheduler, Seen& out, Draws& d, bool own_slot, Again a)
      : s(scheduler), seen(out), draws(d), owned(own_slot), again(a) {
    if (owned) slot = s.own(&TwinOwner::fire_first, this);
  }
  void arm(Time when, bool second = false) {
    const Scheduler::Action action = second ? &TwinOwner::fire_second : &TwinOwner::fire_first;
    if (!owned) {
      id = s.at(when, action, this);
    } else if (again == Again::Deferred) {
      s.defer_owned(slot, when, action);
    } else if (again == Again::LaterEitherAction) {
      s.arm_owned(slot, when, action);
    } else {
      s.arm_owned(slot, when);
    }
    armed = true;
  }
  void arm_now() {
    if (armed) return;
    if (owned) {
      s.arm_owned_now(slot);
    } else {
      id = s.at(s.now(), &TwinOwner::fire_first, this);
    }
    armed = true;
  }
  void move(Time when) {
    if (owned) {
      s.move_owned(slot, when);
    } else {
      EXPECT_TRUE(s.move(id, when));
    }
  }
  void cancel() {
    if (owned) {
      s.cancel_owned(slot);
    } else {
      s.cancel(id);
    }
    armed = false;
  }
  void fire(int kind) {
    armed = false;
    seen.emplace_back(s.now(), kind * 1000000 + label++);
    const std::uint32_t r = draws.next();
    const Time soon = s.now() + static_cast<Time>((r >> 12) % 4) * 10;
    switch (again) {
      case Again::Later:
        if ((r >> 8) % 2 == 0) arm(soon);
        break;
      case Again::Now:
        if ((r >> 8) % 3 == 0) arm_now();  // again, right after itself
        break;
      case Again::LaterEitherAction:
      case Again::Deferred:
        if ((r >> 8) % 2 == 0) arm(soon, (r >> 16) % 2 == 1);
        break;
    }
  }
  static void fire_first(void* self) { static_cast<TwinOwner*>(self)->fire(1); }
  static void fire_second(void* self) { static_cast<TwinOwner*>(self)->fire(2); }
};

// Mostly near, sometimes past the scheduler's horizon (a far entry).
Time near_or_far(Draws& draws) {
  return draws.below(8) == 0 ? static_cast<Time>(draws.below(3) + 1) * 100 * kMicrosecond
                             : static_cast<Time>(draws.below(8)) * 10;
}

// How far the scheduler runs between steps: mostly a little, sometimes past the horizon.
Time run_step(Draws& draws) {
  return draws.below(10) == 0 ? 150 * kMicrosecond : static_cast<Time>(draws.below(4)) * 10;
}

// Up to four events that only note when they ran, each `delay()` from now.
template <class Delay>
void add_noting_events(Scheduler& s, Seen& seen, Draws& draws, int& label, Delay delay) {
  for (std::uint32_t i = draws.below(5); i > 0; --i) {
    const Time when = s.now() + delay();
    const int mine = label++;
    s.at(when, [&s, &seen, mine] { seen.emplace_back(s.now(), mine); });
  }
}

// `run(seed, owned)` for 50 seeds: with the owned slot and through EventIds, the same.
template <class Run>
void expect_twins_agree(Run run, std::uint32_t seed_step) {
  for (std::uint32_t seed = 1; seed <= 50; ++seed) {
    EXPECT_EQ(run(seed * seed_step, true), run(seed * seed_step, false)) << "seed " << seed;
  }
}

// arm_owned() and cancel_owned(): the owner armed from outside and again from its action,
// cancelled, among other events.
Seen run_owned_twin(std::uint32_t seed, bool owned) {
  Scheduler s;
  Seen seen;
  Draws draws{seed};
  TwinOwner owner(s, seen, draws, owned, TwinOwner::Again::Later);
  int label = 0;
  for (int round = 0; round < 200; ++round) {
    add_noting_events(s, seen, draws, label,
                      [&draws] { return static_cast<Time>(draws.below(8)) * 10; });
    const std::uint32_t what = draws.below(4);
    if (what == 0 && !owner.armed) owner.arm(s.now() + static_cast<Time>(draws.below(8)) * 10);
    if (what == 1 && owner.armed) owner.cancel();
    s.run_until(s.now() + static_cast<Time>(draws.below(4)) * 10);
  }
  s.run_until(s.now() + 1000);
  return seen;
}

TEST(Scheduler, AnOwnedSlotRunsAsAtWouldThroughRandomSteps) {
  expect_twins_agree(run_owned_twin, 7919u);
}

// arm_owned_now() against at(now()): the owned event armed for now from other events, from
// its own action and between runs (when now may lie past the queue's near part), cancelled
// at times, among events near and far.
Seen run_owned_now_twin(std::uint32_t seed, bool owned) {
  Scheduler s;
  Seen seen;
  Draws draws{seed};
  TwinOwner owner(s, seen, draws, owned, TwinOwner::Again::Now);
  int label = 0;
  // Some events arm the owner for now or cancel it when they run.
  std::function<void(int, std::uint32_t)> event = [&](int mine, std::uint32_t what) {
    seen.emplace_back(s.now(), mine);
    if (what == 0) owner.arm_now();
    if (what == 1 && owner.armed) owner.cancel();
    if (what == 2) {  // schedules another for now or soon, which may arm the owner
      const int next = label++;
      const std::uint32_t next_what = draws.below(4);
      s.at(s.now() + static_cast<Time>(draws.below(3)) * 10,
           [&event, next, next_what] { event(next, next_what); });
    }
  };
  for (int round = 0; round < 300; ++round) {
    for (std::uint32_t i = draws.below(5); i > 0; --i) {
      const Time delay = near_or_far(draws);
      const int mine = label++;
      const std::uint32_t what = draws.below(5);
      s.at(s.now() + delay, [&event, mine, what] { event(mine, what); });
    }
    if (draws.below(6) == 0) owner.arm_now();
    s.run_until(s.now() + run_step(draws));
  }
  s.run_until(s.now() + kMillisecond);
  return seen;
}

TEST(Scheduler, AnOwnedSlotArmedForNowRunsAsAtWouldThroughRandomSteps) {
  expect_twins_agree(run_owned_now_twin, 104729u);
}

// arm_owned() with an action per arm and move_owned() against at() and move(): the owned
// event armed with one of two actions (from outside and from its own action), moved,
// cancelled, among events near and far.
Seen run_owned_action_twin(std::uint32_t seed, bool owned) {
  Scheduler s;
  Seen seen;
  Draws draws{seed};
  TwinOwner owner(s, seen, draws, owned, TwinOwner::Again::LaterEitherAction);
  int label = 0;
  for (int round = 0; round < 300; ++round) {
    add_noting_events(s, seen, draws, label, [&draws] { return near_or_far(draws); });
    const std::uint32_t what = draws.below(5);
    if (what == 0 && !owner.armed) owner.arm(s.now() + near_or_far(draws), draws.below(2) == 1);
    if (what == 1 && owner.armed) owner.cancel();
    if (what == 2 && owner.armed) owner.move(s.now() + near_or_far(draws));
    s.run_until(s.now() + run_step(draws));
  }
  s.run_until(s.now() + kMillisecond);
  return seen;
}

TEST(Scheduler, AnOwnedSlotWithAnActionPerArmMovedRunsAsAtAndMoveWouldThroughRandomSteps) {
  expect_twins_agree(run_owned_action_twin, 15485863u);
}

// The owned event of the fixed-order tests below: notes 'd' in the order string it is given.
void note_d(void* order) { static_cast<std::string*>(order)->push_back('d'); }

// A deferred event runs where arm_owned() at its deferral would have put it: after the events
// of its time scheduled before, before those scheduled after, also those moved to its time
// afterwards, whether they wait near the front of the queue or far ahead of it.
TEST(Scheduler, ADeferredEventRunsWhereArmingItThenWouldHavePutIt) {
  Scheduler s;
  std::string order;
  const Scheduler::Action note = &note_d;
  const Scheduler::OwnedSlot slot = s.own(note, &order);
  // Far ahead of the queue's front (a new scheduler queues everything far at first).
  const Time far = kMillisecond;
  s.at(far, [&] { order.push_back('a'); });
  s.defer_owned(slot, far, note);
  s.at(far, [&] { order.push_back('b'); });
  const auto moved = s.at(far + 10, [&] { order.push_back('c'); });
  EXPECT_TRUE(s.move(moved, far));
  s.run_until(far);
  EXPECT_EQ(order, "adbc");
  // Near the front.
  s.at(far + 20, [&] { order.push_back('e'); });
  s.defer_owned(slot, far + 20, note);
  const auto moved_too = s.at(far + 30, [&] { order.push_back('g'); });
  s.at(far + 20, [&] { order.push_back('f'); });
  EXPECT_TRUE(s.move(moved_too, far + 20));
  s.run_until(far + 20);
  EXPECT_EQ(order, "adbcedfg");
  // Deferred, then moved: as if armed anew at the move.
  s.defer_owned(slot, far + 40, note);
  s.at(far + 50, [&] { order.push_back('h'); });
  s.move_owned(slot, far + 50);
  s.run_until(far + 50);
  EXPECT_EQ(order, "adbcedfghd");
}

// One of the recorded events moved to `when` (the owner's time), if there is one.
void move_one_to(Scheduler& s, Draws& draws, const std::vector<Scheduler::EventId>& ids,
                 Time when) {
  if (ids.empty()) return;
  static_cast<void>(s.move(ids[draws.below(static_cast<std::uint32_t>(ids.size()))], when));
}

// Runs on a little: one step now and then (when the next event is close), mostly run_until().
void step_or_run(Scheduler& s, Draws& draws) {
  if (draws.below(4) == 0) {
    const std::optional<Time> next = s.next_time();
    if (next && *next <= s.now() + 100) s.step();
  } else {
    s.run_until(s.now() + run_step(draws));
  }
}

// defer_owned() against at(): the owned event deferred (from outside and from its own
// action, with either action), cancelled and moved, among events near and far that are
// often due at its very time: scheduled before and after it was deferred, some of them
// moved to its time, from outside and from events; run by run_until() and step().
Seen run_deferred_twin(std::uint32_t seed, bool owned) {
  Scheduler s;
  Seen seen;
  Draws draws{seed};
  TwinOwner owner(s, seen, draws, owned, TwinOwner::Again::Deferred);
  Time owner_when = 0;  // the owner's time when it was last armed or moved
  int label = 0;
  std::vector<Scheduler::EventId> ids;
  // A noting event at `when` that may schedule another at the owner's time when it runs.
  std::function<void(Time)> add = [&](Time when) {
    const int mine = label++;
    const bool more = draws.below(3) == 0;
    ids.push_back(s.at(when, [&, mine, more] {
      seen.emplace_back(s.now(), mine);
      if (more && owner_when >= s.now()) add(owner_when);
    }));
  };
  for (int round = 0; round < 300; ++round) {
    for (std::uint32_t i = draws.below(4); i > 0; --i) add(s.now() + near_or_far(draws));
    const std::uint32_t what = draws.below(6);
    if (what == 0 && !owner.armed) {
      owner_when = s.now() + near_or_far(draws);
      owner.arm(owner_when, draws.below(2) == 1);
    }
    if (what == 1 && owner.armed) owner.cancel();
    if (what == 2 && owner.armed) {
      owner_when = s.now() + near_or_far(draws);
      owner.move(owner_when);
    }
    // Others due at the owner's time, queued now or moved there.
    if (what == 3 && owner_when >= s.now()) add(owner_when);
    if (what == 4 && owner_when >= s.now()) move_one_to(s, draws, ids, owner_when);
    step_or_run(s, draws);
  }
  s.run_until(s.now() + kMillisecond);
  return seen;
}

TEST(Scheduler, ADeferredOwnedEventRunsAsAtWouldThroughRandomSteps) {
  expect_twins_agree(run_deferred_twin, 7907u);
}

// An event may run the scheduler itself (run_until inside run_until). The outer run still
// stops at its own time: an event deferred after the inner run returned (which bounds how
// far the run goes before it must queue deferred events) does not carry it past that time.
TEST(Scheduler, ARunInsideAnEventLeavesTheOuterRunItsOwnEnd) {
  Scheduler s;
  std::string order;
  const Scheduler::Action note = &note_d;
  const Scheduler::OwnedSlot slot = s.own(note, &order);
  s.at(10, [&] {
    order.push_back('a');
    s.run_until(20);
  });
  s.at(30, [&] {
    order.push_back('b');
    s.defer_owned(slot, 500, note);
  });
  s.at(200, [&] { order.push_back('c'); });
  s.run_until(100);
  EXPECT_EQ(order, "ab");
  EXPECT_EQ(s.now(), 100);
  s.run_until(1000);
  EXPECT_EQ(order, "abcd");
}

// hold_owned() against at(): an owner whose event sets a flag (INT_TEND) holds it while the
// flag is set and queues it (queue_held()) when an event clears the flag. Events note the
// flag when they run; clears and notes are often due at the owner's very time, scheduled
// before and after its hold, some moved there; the owner is armed from outside and from
// events (also for now), cancelled and moved; run by run_until() and step(). Some holds
// are lazy (hold_owned_lazily), their time given by the owner when asked; some are held anew
// (hold_owned_anew) over the last one, pending or not.
struct HeldOwner {
  Scheduler& s;
  bool& flag;
  bool held_form;
  Scheduler::OwnedSlot slot = 0;
  Scheduler::EventId id{};
  bool held = false;

  HeldOwner(Scheduler& scheduler, bool& f, bool hold) : s(scheduler), flag(f), held_form(hold) {
    if (held_form) slot = s.own(&HeldOwner::raise, this);
  }
  Time lazy_when = 0;  // a lazy hold's time, given when asked (resolve)

  static void raise(void* self) { static_cast<HeldOwner*>(self)->flag = true; }
  static Time resolve(void* self) { return static_cast<HeldOwner*>(self)->lazy_when; }
  bool pending() const {
    if (!held_form) return s.pending(id);
    return s.owned_pending(slot) && !(held && s.held_passed(slot));
  }
  void arm(Time when) {
    if (!held_form) {
      id = s.at(when, &HeldOwner::raise, this);
      return;
    }
    // Every 40 ps from 10 on held again in one call (cancel and hold: hold_owned_anew).
    if (flag && when / 10 % 4 == 1) {
      s.hold_owned_anew(slot, when);
      held = true;
      return;
    }
    if (s.owned_pending(slot)) s.cancel_owned(slot);  // a passed held one
    if (flag) {
      // Every other 10 ps held lazily: its time known only when asked.
      if (when / 10 % 2 == 0) {
        lazy_when = when;
        s.hold_owned_lazily(slot, &HeldOwner::raise, &HeldOwner::resolve);
      } else {
        s.hold_owned(slot, when, &HeldOwner::raise);
      }
      held = true;
      return;
    }
    if (held) s.queue_held(slot);
    held = false;
    s.arm_owned(slot, when);
  }
  void cancel() {
    if (held_form) {
      s.cancel_owned(slot);
    } else {
      s.cancel(id);
    }
  }
  void move(Time when) {
    if (!held_form) {
      EXPECT_TRUE(s.move(id, when));
      return;
    }
    held = false;
    s.move_owned(slot, when);
  }
  void cleared() {
    if (!held_form || !held) return;
    held = false;
    s.queue_held(slot);
  }
};

Seen run_held_twin(std::uint32_t seed, bool held_form) {
  Scheduler s;
  Seen seen;
  Draws draws{seed};
  bool flag = true;
  HeldOwner owner(s, flag, held_form);
  Time owner_when = 0;
  int label = 0;
  std::vector<Scheduler::EventId> ids;
  // An event at `when` that notes the flag, clears it (kind 1) or arms the owner (kind 2).
  std::function<void(Time)> add = [&](Time when) {
    const int mine = label++;
    const std::uint32_t kind = draws.below(4);
    const Time later = static_cast<Time>(draws.below(4)) * 10;
    ids.push_back(s.at(when, [&, mine, kind, later] {
      seen.emplace_back(s.now(), mine * 2 + (flag ? 1 : 0));
      if (kind == 1) {
        flag = false;
        owner.cleared();
      } else if (kind == 2 && !owner.pending()) {
        owner_when = s.now() + later;
        owner.arm(owner_when);
      }
    }));
  };
  for (int round = 0; round < 400; ++round) {
    for (std::uint32_t i = draws.below(4); i > 0; --i) add(s.now() + near_or_far(draws));
    const std::uint32_t what = draws.below(7);
    if (what == 0 && !owner.pending()) {
      owner_when = s.now() + near_or_far(draws);
      owner.arm(owner_when);
    }
    if (what == 1 && owner.pending()) owner.cancel();
    if (what == 2 && owner.pending()) {
      owner_when = s.now() + near_or_far(draws);
      owner.move(owner_when);
    }
    if (what == 3 && owner_when >= s.now()) add(owner_when);
    if (what == 4 && owner_when >= s.now()) move_one_to(s, draws, ids, owner_when);
    if (what == 5) {  // a clear from outside
      flag = false;
      owner.cleared();
    }
    seen.emplace_back(s.now(), owner.pending() ? -1 : -2);
    step_or_run(s, draws);
  }
  s.run_until(s.now() + kMillisecond);
  seen.emplace_back(s.now(), flag ? -3 : -4);
  return seen;
}

TEST(Scheduler, AHeldOwnedEventActsAsAtWouldThroughRandomSteps) {
  expect_twins_agree(run_held_twin, 7919u);
}

// A lazy hold whose time proves to be over (kUnheld) never runs: not pending once asked,
// passed, and queue_held() queues nothing. Held lazily again with a time ahead, it is queued.
TEST(Scheduler, ALazilyHeldEventOverWhenHeldNeverRuns) {
  struct Owner {
    int runs = 0;
    Time when = Scheduler::kUnheld;
    static void run(void* o) { ++static_cast<Owner*>(o)->runs; }
    static Time resolve(void* o) { return static_cast<Owner*>(o)->when; }
  } owner;
  Scheduler s;
  const auto slot = s.own(&Owner::run, &owner);
  s.run_until(100);
  s.hold_owned_lazily(slot, &Owner::run, &Owner::resolve);
  EXPECT_TRUE(s.owned_pending(slot));
  EXPECT_TRUE(s.held_passed(slot));
  EXPECT_EQ(s.pending_count(), 0u);
  s.queue_held(slot);
  EXPECT_FALSE(s.owned_pending(slot));
  s.run_until(1000);
  EXPECT_EQ(owner.runs, 0);
  owner.when = 2000;
  s.hold_owned_lazily(slot, &Owner::run, &Owner::resolve);
  EXPECT_EQ(s.pending_count(), 1u);
  EXPECT_FALSE(s.held_passed(slot));
  s.queue_held(slot);
  EXPECT_EQ(s.next_time(), 2000);
  s.run_until(3000);
  EXPECT_EQ(owner.runs, 1);
}

TEST(Time, BitAndClockPeriodsAreExactPicoseconds) {
  EXPECT_EQ(period_of_hz(16'000'000), 62'500);  // 16 Mbit/s bit: 62.5 ns
  EXPECT_EQ(period_of_hz(64'000'000), 15'625);  // 64 MHz MCLK: 15.625 ns
  EXPECT_EQ(period_of_hz(2'000'000), 500 * kNanosecond);
}

}  // namespace
}  // namespace sercon::sim

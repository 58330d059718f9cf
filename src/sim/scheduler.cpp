#include "sercon/sim/scheduler.hpp"

#include <algorithm>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>

#include "sercon/sim/signal.hpp"

namespace sercon::sim {
namespace {

[[noreturn, gnu::cold, gnu::noinline]] void throw_past(const char* what, Time when, Time now) {
  throw std::invalid_argument(std::string(what) + ": time " + std::to_string(when) +
                              " ps is before now (" + std::to_string(now) + " ps)");
}

}  // namespace

void Scheduler::refuse_past(const char* what, Time when) const { throw_past(what, when, now_); }
void Scheduler::refuse_past_or_null(const char* what, Time when) const {
  if (when < now_) throw_past(what, when, now_);
  throw std::invalid_argument(std::string(what) + ": no action given");
}

void Scheduler::refuse_arm(const char* what, OwnedSlot owned, Time when) const {
  if (when < now_) throw_past(what, when, now_);
  throw std::logic_error(std::string(what) + ": owned slot " + std::to_string(owned) +
                         " is pending already (cancel_owned() it before arming it again)");
}

[[gnu::noinline]] std::uint32_t Scheduler::new_slot() {
  slots_.emplace_back();
  return static_cast<std::uint32_t>(slots_.size() - 1);
}

// The storage is full: drop the entries that have run when they are at least half of
// it, otherwise grow.
void Scheduler::SortedRun::make_room() {
  const std::size_t h = head_index();
  const std::size_t t = tail_index();
  if (h > 0 && h * 2 >= t) {
    std::copy(head, tail, buffer.data());
    place(0, t - h);
  } else {
    buffer.resize(std::max<std::size_t>(16, buffer.size() * 2));
    place(h, t);
  }
}

// After every entry at or before `when`: same-time events run in scheduling order.
void Scheduler::SortedRun::insert(const Entry& entry) {
  std::size_t h = head_index();
  std::size_t t = tail_index();
  insert_indexed(entry, h, t);
  place(h, t);
}

// insert() on the run buffer[h, t), which it updates (make_room() sees it placed).
void Scheduler::SortedRun::insert_indexed(const Entry& entry, std::size_t& h, std::size_t& t) {
  const auto make_room = [&] {
    place(h, t);
    this->make_room();
    h = head_index();
    t = tail_index();
  };
  const Time when = entry.when;
  if (h == t) {
    h = t = 0;
  } else if (when < buffer[t - 1].when) {
    // A few places behind the front: walk there as Scheduler::insert does, once there is
    // room before the front. Further in, a binary search.
    if (t - h <= kWalk || when < buffer[h + kWalk].when) {
      if (h == 0) {  // room for this entry and the next few late-comers
        // With h 0, make_room() grows; more than once if kWalk outgrows a doubling.
        while (t + kWalk > buffer.size()) make_room();
        std::copy_backward(buffer.data(), buffer.data() + t, buffer.data() + t + kWalk);
        h += kWalk;
        t += kWalk;
      }
      Entry* at = buffer.data() + h;
      for (; at->when <= when; ++at) at[-1] = *at;
      at[-1] = entry;
      --h;
      return;
    }
    Entry* const first = buffer.data() + h;
    Entry* const last = buffer.data() + t;
    // Branch-free upper bound: the first entry later than `when` (one exists).
    Entry* base = first;
    for (std::size_t n = t - h; n > 1;) {
      const std::size_t half = n / 2;
      base = base[half].when <= when ? base + half : base;
      n -= half;
    }
    Entry* const at = base + (base->when <= when);
    // Move the shorter side: the entries before `at` one place towards those that have
    // run, or those from `at` on one place back.
    if (h > 0 && at - first <= last - at) {
      std::copy(first, at, first - 1);
      at[-1] = entry;
      --h;
      return;
    }
    if (t == buffer.size()) {
      const std::size_t offset = static_cast<std::size_t>(at - first);
      make_room();
      Entry* const moved = buffer.data() + h + offset;
      std::copy_backward(moved, buffer.data() + t, buffer.data() + t + 1);
      *moved = entry;
    } else {
      std::copy_backward(at, last, last + 1);
      *at = entry;
    }
    ++t;
    return;
  }
  if (t == buffer.size()) make_room();
  buffer[t++] = entry;
}

// Before the first entry of its time scheduled after it (generations tell: the entries of
// a time scheduled before a deferred event come before those scheduled after it), else
// after the entries of its time.
void Scheduler::SortedRun::insert_deferred(const Entry& entry) {
  Entry* const last = tail;
  Entry* at =
      std::lower_bound(head, last, entry.when, [](const Entry& e, Time t) { return e.when < t; });
  while (at != last && at->when == entry.when && earlier(at->generation, entry.generation)) ++at;
  const std::ptrdiff_t offset = at - head;
  if (tail == end) make_room();
  Entry* const to = head + offset;
  std::copy_backward(to, tail, tail + 1);
  *to = entry;
  ++tail;
}

void Scheduler::LaterEntries::insert_deferred(const Entry& entry) {
  const auto at = std::find_if(entries.begin(), entries.end(), [&](const Entry& e) {
    return e.when == entry.when && earlier(entry.generation, e.generation);
  });
  entries.insert(at, entry);
  earliest = std::min(earliest, entry.when);
}

// Takes a pending event's entry out (it is there: live entries are never passed over).
// The live entry: a cancelled event's entry may still sit at the same time with the same
// slot (reused since), told apart by its generation.
void Scheduler::SortedRun::remove(Time when, std::uint32_t slot, Generation generation) {
  Entry* const last = tail;
  Entry* at = std::lower_bound(head, last, when, [](const Entry& e, Time t) { return e.when < t; });
  while (at->slot != slot || at->generation != generation) ++at;
  std::copy(at + 1, last, at);
  --tail;
}

// Takes a pending event's entry out of far_ (it is there), keeping the others' order.
void Scheduler::LaterEntries::remove(std::uint32_t slot, Generation generation) {
  const auto at = std::find_if(entries.begin(), entries.end(), [&](const Entry& e) {
    return e.slot == slot && e.generation == generation;
  });
  entries.erase(at);
}

// near_'s first n entries, in order up to `sorted`, sorted by time, stably (same-time
// entries keep their order). They come as a few runs in order (those queued one cycle and
// the next): each run is merged into those before it, into scratch_, which then becomes
// near_'s buffer; a run wholly earlier than those before it simply goes first. More runs
// than that take a merge sort.
void Scheduler::sort_near(std::size_t sorted, std::size_t n) {
  const auto earlier = [](const Entry& a, const Entry& b) { return a.when < b.when; };
  Entry* first = near_.buffer.data();
  for (int runs = 1; sorted != n; ++runs) {
    if (runs == kMergedRuns) {
      std::stable_sort(first, first + n, earlier);
      return;
    }
    const std::size_t run_end =
        static_cast<std::size_t>(std::is_sorted_until(first + sorted, first + n, earlier) - first);
    if (scratch_.size() < near_.buffer.size()) scratch_.resize(near_.buffer.size());
    Entry* merged = scratch_.data();
    if (first[run_end - 1].when < first[0].when) {
      merged = std::copy(first + sorted, first + run_end, merged);
      merged = std::copy(first, first + sorted, merged);
    } else {
      // On equal times std::merge takes the first range's entry: the one queued first.
      merged = std::merge(first, first + sorted, first + sorted, first + run_end, merged, earlier);
    }
    std::copy(first + run_end, first + n, merged);  // the runs still to merge
    near_.buffer.swap(scratch_);
    near_.place(0, n);
    first = near_.buffer.data();
    sorted = run_end;
  }
}

// near_ is empty: move the limit past the earliest far entry and bring the entries up
// to it over, sorted by time (those of cancelled events are dropped).
void Scheduler::refill() {
  std::vector<Entry>& later = far_.entries;
  // far_.earliest may be a cancelled entry's time, never later than the earliest live one:
  // then fewer move (maybe none: front() comes back with the limit worked out here).
  const Time earliest = far_.earliest;
  near_limit_ = earliest > std::numeric_limits<Time>::max() - (kHorizon - 1)
                    ? std::numeric_limits<Time>::max()
                    : earliest + (kHorizon - 1);
  if (near_.buffer.size() < later.size()) near_.buffer.resize(later.size());
  // The live entries up to the limit to near_, the others stay, both in order; then near_
  // sorted by time, stably (mostly they come in order already).
  Entry* const first = near_.buffer.data();
  Entry* to = first;
  Entry* in_order_end = nullptr;  // the first entry out of order, if any
  Time stays_earliest = std::numeric_limits<Time>::max();
  auto stay = later.begin();
  for (const Entry& entry : later) {
    if (slots_[entry.slot].generation != entry.generation) continue;  // cancelled
    if (entry.when <= near_limit_) {
      if (in_order_end == nullptr && to != first && entry.when < to[-1].when) in_order_end = to;
      *to++ = entry;
    } else {
      stays_earliest = std::min(stays_earliest, entry.when);
      *stay++ = entry;
    }
  }
  later.erase(stay, later.end());
  far_.earliest = stays_earliest;
  const auto n = static_cast<std::size_t>(to - first);
  near_.place(0, n);
  if (in_order_end != nullptr) sort_near(static_cast<std::size_t>(in_order_end - first), n);
}

void Scheduler::insert_now(std::uint32_t slot, Generation generation) {
  insert(now_, slot, generation);
}

Scheduler::EventId Scheduler::at(Time when, Callback callback) {
  if (when < now_) throw_past("Scheduler::at", when, now_);
  const std::uint32_t index = free_slot_index();
  Slot& slot = slots_[index];
  slot.action = nullptr;
  if (callbacks_.size() <= index) callbacks_.resize(slots_.size());
  callbacks_[index] = std::move(callback);
  return take_slot(index, when);
}

Scheduler::OwnedSlot Scheduler::own(Action action, void* context) {
  // A slot given back before may be taken: its generation only grows, so no stale EventId
  // names it.
  const std::uint32_t index = free_slot_index();
  Slot& slot = slots_[index];
  free_head_ = slot.next_free;
  slot.action = action;
  slot.context = context;
  slot.next_free = kOwned;
  return index;
}

void Scheduler::disown(OwnedSlot owned) {
  cancel_owned(owned);  // even: not pending
  Slot& slot = slots_[owned];
  if ((slot.next_free & kListed) != 0) std::erase(held_, owned);
  if ((slot.next_free & kResolver) != 0)
    std::erase_if(resolvers_, [&](const Resolver& r) { return r.slot == owned; });
  slot.context = nullptr;
  ++slot.generation;  // odd, as a taken slot's: free_slot() makes it even again
  free_slot(owned);   // and links it (next_free no longer marks it owned)
}

std::size_t Scheduler::pending_count() const {
  return static_cast<std::size_t>(
      std::count_if(slots_.begin(), slots_.end(), [&](const Slot& slot) {
        return slot.generation % 2 == 1 &&
               !(held(slot) && passed_or_over(static_cast<std::uint32_t>(&slot - slots_.data())));
      }));
}

Time Scheduler::held_when(std::uint32_t index) const {
  const Slot& slot = slots_[index];
  // A cancelled slot may keep kLazy: its resolver's owner may be gone.
  if ((slot.next_free & kLazy) == 0 || !held(slot)) return slot.when;
  for (const Resolver& r : resolvers_) {
    if (r.slot == index) return r.resolve(slot.context);
  }
  return slot.when;  // not reached: a lazy slot is in resolvers_
}

void Scheduler::settle_lazy(std::uint32_t index) {
  Slot& slot = slots_[index];
  if ((slot.next_free & kLazy) == 0) return;
  if (held(slot)) {
    const Time when = held_when(index);
    if (when == kUnheld) {
      slot.next_free &= ~(kHeld | kLazy);
      ++slot.generation;  // over when it was held: it never runs
      return;
    }
    slot.when = when;
  }
  slot.next_free &= ~kLazy;
}

bool Scheduler::resolver_is(OwnedSlot owned, Resolve resolve) const {
  for (const Resolver& r : resolvers_) {
    if (r.slot == owned) return r.resolve == resolve;
  }
  return true;  // none yet: list_resolver() lists it
}

void Scheduler::list_resolver(OwnedSlot owned, Resolve resolve) {
  Slot& slot = slots_[owned];
  if ((slot.next_free & kListed) == 0) held_.push_back(owned);
  if ((slot.next_free & kResolver) == 0) resolvers_.push_back(Resolver{owned, resolve});
}

void Scheduler::queue_held_slot(std::uint32_t index) {
  Slot& slot = slots_[index];
  slot.next_free &= ~kHeld;
  place_deferred(Entry{slot.when, index, slot.generation});
}

void Scheduler::queue_held(OwnedSlot owned) {
  settle_lazy(owned);
  Slot& slot = slots_[owned];
  if (!held(slot)) return;
  if (passed(slot)) {
    slot.next_free &= ~kHeld;
    ++slot.generation;  // it has run
    return;
  }
  queue_held_slot(owned);
}

bool Scheduler::queue_held_through(Time next) {
  bool queued = false;
  for (const std::uint32_t index : held_) {
    settle_lazy(index);
    const Slot& slot = slots_[index];
    if (held(slot) && slot.when <= next && !passed(slot)) {
      queue_held_slot(index);
      queued = true;
    }
  }
  return queued;
}

// Before a move to `when`: the held events due then and still ahead go into the queue, each
// in its place, so the moved event comes after them.
void Scheduler::queue_held_at(Time when) {
  for (const std::uint32_t index : held_) {
    settle_lazy(index);
    const Slot& slot = slots_[index];
    if (held(slot) && slot.when == when && !passed(slot)) queue_held_slot(index);
  }
}

bool Scheduler::move(EventId id, Time when) {
  if (when < now_) throw_past("Scheduler::move", when, now_);
  if (live_slot(id) == nullptr) return false;
  requeue(id.slot, when);
  return true;
}

void Scheduler::move_owned(OwnedSlot owned, Time when) {
  if (when < now_) throw_past("Scheduler::move_owned", when, now_);
  settle_lazy(owned);  // one over when it was held is not pending
  if (!owned_pending(owned)) {
    throw std::logic_error("Scheduler::move_owned: owned slot " + std::to_string(owned) +
                           " is not pending");
  }
  requeue(owned, when);
}

// A moved event keeps its generation (its EventId), so the deferred events due at `when`,
// scheduled before the move, are queued first. A deferred event moved is queued now.
void Scheduler::requeue(std::uint32_t index, Time when) {
  Slot& slot = slots_[index];
  if (held(slot)) {  // no queue entry to take out; once passed, it has run: not pending
    slot.next_free &= ~kHeld;
    if (passed(slot)) {
      ++slot.generation;
      throw std::logic_error("Scheduler::move_owned: owned slot " + std::to_string(index) +
                             " is not pending");
    }
  } else {
    const auto deferred = std::find_if(
        deferred_.begin() + static_cast<std::ptrdiff_t>(deferred_head_), deferred_.end(),
        [&](const Entry& e) { return e.slot == index && e.generation == slot.generation; });
    if (deferred != deferred_.end()) {
      deferred_.erase(deferred);
    } else if (slot.when <= near_limit_) {
      near_.remove(slot.when, index, slot.generation);
    } else {
      far_.remove(index, slot.generation);
    }
  }
  if (!held_.empty()) queue_held_at(when);
  queue_deferred_at(when);
  slot.when = when;
  insert(when, index, slot.generation);
}

// defer_owned() refused, due now, or before the last deferred event.
void Scheduler::defer_owned_slowly(OwnedSlot owned, Time when, Action action) {
  if (when < now_ || owned_pending(owned)) refuse_arm("Scheduler::defer_owned", owned, when);
  Slot& slot = slots_[owned];
  const Entry entry{when, owned, take_order(slot, when)};
  slot.action = action;
  if (!deferred_waiting() || when >= deferred_.back().when) {
    deferred_.push_back(entry);
    deferred_last_ = std::max(deferred_last_, when);
  } else {  // after those of its time, deferred before it
    const auto at =
        std::upper_bound(deferred_.begin() + static_cast<std::ptrdiff_t>(deferred_head_),
                         deferred_.end(), when, [](Time t, const Entry& e) { return t < e.when; });
    deferred_.insert(at, entry);
  }
  // Due now, the run may be at its time already: queued at once.
  if (when == now_) return queue_deferred_at(when);
  stop_ = std::min(stop_, when - 1);
}

void Scheduler::place_deferred(const Entry& entry) {
  if (entry.when <= near_limit_) {
    near_.insert_deferred(entry);
  } else {
    far_.insert_deferred(entry);
  }
}

bool Scheduler::queue_deferred(Time next, Time until) {
  const Time due = std::min(next, until);
  bool queued = false;
  std::size_t i = deferred_head_;
  for (const std::size_t n = deferred_.size(); i != n; ++i) {
    const Entry entry = deferred_[i];
    if (slots_[entry.slot].generation != entry.generation) continue;  // cancelled
    if (entry.when > due) break;
    place_deferred(entry);  // leaves deferred_ as it is
    queued = true;
  }
  deferred_head_ = i;
  compact_deferred_if_due();
  set_stop();
  return queued;
}

void Scheduler::compact_deferred() {
  deferred_.erase(deferred_.begin(),
                  deferred_.begin() + static_cast<std::ptrdiff_t>(deferred_head_));
  deferred_head_ = 0;
}

void Scheduler::queue_deferred_at(Time when) {
  const auto first =
      std::lower_bound(deferred_.begin() + static_cast<std::ptrdiff_t>(deferred_head_),
                       deferred_.end(), when, [](const Entry& e, Time t) { return e.when < t; });
  auto last = first;
  for (; last != deferred_.end() && last->when == when; ++last) {
    if (slots_[last->slot].generation == last->generation) place_deferred(*last);
  }
  deferred_.erase(first, last);
}

void Scheduler::set_stop() {
  const Time first =
      deferred_waiting() ? deferred_[deferred_head_].when : std::numeric_limits<Time>::max();
  stop_ = std::min(until_, first == std::numeric_limits<Time>::max() ? first : first - 1);
}

void Scheduler::release(std::uint32_t index) {
  callbacks_[index] = nullptr;  // release what it captured now
  free_slot(index);
}

// Takes `entry` off the front and runs its event. Inline in the loops below.
inline void Scheduler::run(const Entry& entry) {
  ++near_.head;
  now_ = entry.when;
  running_ = entry.generation;
  Slot& slot = slots_[entry.slot];
  // Take the event out before running it: it may schedule others (slots_ may grow).
  // Owned slots first: nearly every event of a ring is one. The others' index from the
  // slot's address: kept from the entry, it took a register copy at every event.
  if ((slot.next_free & kOwned) != 0) [[likely]] {
    ++slot.generation;  // even: no longer pending (the action may arm it again)
    slot.action(slot.context);
  } else {
    run_unowned(static_cast<std::uint32_t>(&slot - slots_.data()));
  }
}

void Scheduler::run_unowned(std::uint32_t index) {
  Slot& slot = slots_[index];
  if (slot.action == nullptr) return run_callback(index);
  const Action action = slot.action;
  void* const context = slot.context;
  free_slot(index);
  action(context);
}

void Scheduler::run_callback(std::uint32_t index) {
  Callback callback = std::move(callbacks_[index]);
  callbacks_[index] = nullptr;
  free_slot(index);
  callback();
}

// Each event is one batch of signal changes (signal.hpp): what its pins do is heard once
// the event is done, so a watcher never sees a model half-way through an event. One
// Signal::Steps for the run: the batch is not opened and closed again at every event.
// front() and run() in one loop: the entry is looked up once per event, and the slot of the
// generation check is the one run() takes (inline: the compiler loads it once).
void Scheduler::run_until(Time until) {
  if (until < now_) throw_past("Scheduler::run_until", until, now_);
  Signal::Steps steps;
  // An event may run the scheduler itself: the outer run's until_ (and so its stop_) is
  // put back when this one ends, also by an exception.
  struct RestoreUntil {
    Scheduler& scheduler;
    Time outer;
    ~RestoreUntil() {
      scheduler.until_ = outer;
      scheduler.set_stop();
    }
  } restore{*this, until_};
  until_ = until;
  set_stop();
  for (;;) {
    Entry* const head = near_.head;
    if (head == near_.tail) {
      if (far_.empty()) {
        if (deferred_waiting() && queue_deferred(until, until)) continue;
        break;
      }
      refill();
      continue;
    }
    const Entry& entry = *head;
    const std::uint32_t index = entry.slot;
    Slot& slot = slots_[index];
    if (slot.generation != entry.generation) {  // cancelled
      near_.head = head + 1;
      continue;
    }
    // Past `until`, or at a deferred event's time (stop_ is the lower).
    if (entry.when > stop_) [[unlikely]] {
      if (queue_deferred(entry.when, until)) continue;
      if (entry.when > until) break;
    }
    run(entry);
    steps.done();
  }
  now_ = until;
  running_ = generation_;
}

bool Scheduler::step() {
  const Entry* next = front();
  if (next == nullptr) return false;
  Signal::batch([this, next] { run(*next); });
  return true;
}

std::optional<Time> Scheduler::next_time() {
  const Entry* next = front();
  if (next == nullptr) return std::nullopt;
  return next->when;
}

}  // namespace sercon::sim

// A discrete-event scheduler. Events at the same time run in the order they were
// scheduled, so a scenario replays identically (brief: determinism). A deferred event
// (defer_owned) counts as scheduled when it is deferred, though it is queued later.
#pragma once

#include <algorithm>
#include <cassert>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <limits>
#include <optional>
#include <vector>

#include "sercon/sim/time.hpp"

namespace sercon::sim {

class Scheduler {
 public:
  using Callback = std::function<void()>;
  // The allocation-free form for hot users: `action(context)` runs at the event's time.
  using Action = void (*)(void* context);
  // An event's place in the order of scheduling (next_generation()).
  using Generation = std::uint64_t;
  // An event's generation and its slot's index. No two events share a generation (64 bits
  // do not wrap), so a stale id never names a later event; EventId{} names none.
  struct EventId {
    Generation generation = 0;
    std::uint32_t slot = 0;
    friend bool operator==(EventId, EventId) = default;
  };

  Scheduler() = default;
  Scheduler(const Scheduler&) = delete;
  Scheduler& operator=(const Scheduler&) = delete;

  Time now() const { return now_; }

  // Runs `callback` at absolute time `when`; throws std::invalid_argument if `when` is
  // in the past.
  EventId at(Time when, Callback callback);
  // Runs `action(context)` at `when`; same rules. `context` must outlive the event.
  // Inline: most events of a run are scheduled this way.
  EventId at(Time when, Action action, void* context) {
    if (when < now_ || action == nullptr) [[unlikely]]
      refuse_past_or_null("Scheduler::at", when);
    const std::uint32_t index = free_slot_index();
    Slot& slot = slots_[index];
    slot.action = action;  // never null: a null action marks an at() event with a Callback
    slot.context = context;
    return take_slot(index, when);
  }
  // Runs `callback` `delay` picoseconds from now (delay >= 0).
  EventId after(Time delay, Callback callback) { return at(now_ + delay, std::move(callback)); }
  EventId after(Time delay, Action action, void* context) {
    return at(now_ + delay, action, context);
  }

  // An event slot its owner keeps for its life, for an event armed again and again (a
  // receiver's report): arming it takes no slot from the free list and makes no EventId,
  // and running or cancelling it gives nothing back. Armed, it is queued as at() queues an
  // event (after those already due at its time), so the order is the same. Its action
  // may arm it again (it is no longer pending while it runs).
  using OwnedSlot = std::uint32_t;
  OwnedSlot own(Action action, void* context);
  // Queues the owned event at `when`. Throws std::invalid_argument if `when` is in the
  // past, std::logic_error if the event is pending already (cancel_owned() it first).
  // Always inline, with insert(): a receiver's report event arms the next one without a call.
  [[gnu::always_inline]] void arm_owned(OwnedSlot owned, Time when) {
    if (when < now_ || owned_pending(owned)) [[unlikely]]
      refuse_arm("Scheduler::arm_owned", owned, when);
    insert(when, owned, take_order(slots_[owned], when));
  }
  // arm_owned(owned, now()): the owned event runs right after the events already due now
  // (the one running, then those queued for now before it), as at(now(), ...) would. Inline
  // (a slave's MST recognised at its load edge): mostly the queue's front is later than now,
  // and the entry goes just before it without a search.
  void arm_owned_now(OwnedSlot owned) {
    if (owned_pending(owned)) [[unlikely]]
      refuse_arm("Scheduler::arm_owned_now", owned, now_);
    const Generation generation = take_order(slots_[owned], now_);
    SortedRun& run = near_;
    if (run.head != run.buffer.data() && now_ <= near_limit_ &&
        (run.head == run.tail || run.head->when > now_)) {
      *--run.head = Entry{now_, owned, generation};
      return;
    }
    insert_now(owned, generation);
  }
  // arm_owned() with `action` for this arm: an owner whose one pending event does one of
  // several things (a list walk's transmit or end marker). The slot keeps it for later arms.
  void arm_owned(OwnedSlot owned, Time when, Action action) {
    arm_owned(owned, when);  // first: refused, it leaves the slot's action as it was
    slots_[owned].action = action;
  }
  // arm_owned(owned, when, action) for a caller that knows `when` is after now and the event
  // not pending (TimeBase's owned events, armed only once their last has run or was
  // cancelled): neither is tested (asserted in debug builds). Inline: a list walk arms one
  // at every transmit header.
  [[gnu::always_inline]] void arm_owned_idle(OwnedSlot owned, Time when, Action action) {
    assert(when > now_);
    slots_[owned].action = action;  // before: nothing is refused (arm_owned() sets it after)
    arm_owned_idle(owned, when);
  }
  // arm_owned(owned, when) for a caller that knows `when` is not before now and the event
  // not pending (a receiver's report, armed only while none is planned): neither is tested
  // (asserted in debug builds). Always inline: a ring arms one at almost every read.
  [[gnu::always_inline]] void arm_owned_idle(OwnedSlot owned, Time when) {
    assert(when >= now_ && !owned_pending(owned));
    insert(when, owned, take_order(slots_[owned], when));
  }
  // arm_owned(owned, when, action) without a queue entry until the run comes to `when` (or
  // something is moved to `when`): the event then takes the place among the events due at
  // `when` that arm_owned() would have given it now (after those scheduled before it,
  // before those scheduled after). For an event mostly cancelled long before it is due (a
  // slave's window close, a cycle ahead), which then never enters the queue. Same rules as
  // arm_owned(); cancel_owned(), move_owned() and disown() take it as any other.
  // Inline: mostly it goes at the back of the deferred events.
  void defer_owned(OwnedSlot owned, Time when, Action action) {
    if (when <= now_ || owned_pending(owned)) [[unlikely]]
      return defer_owned_slowly(owned, when, action);
    defer_idle_owned(owned, when, action);
  }
  // defer_owned() for a caller that knows `when` is after now and the event not pending (as
  // arm_owned_idle()): neither is tested (asserted in debug builds).
  [[gnu::always_inline]] void defer_idle_owned(OwnedSlot owned, Time when, Action action) {
    assert(when > now_ && !owned_pending(owned));
    if (when < deferred_last_) [[unlikely]]
      return defer_owned_slowly(owned, when, action);
    Slot& slot = slots_[owned];
    const Generation generation = take_order(slot, when);
    slot.action = action;
    deferred_.push_back(Entry{when, owned, generation});
    deferred_last_ = when;
    // Mostly the first deferred event is this owner's last one, cancelled since (a slave's
    // window close, dropped by its next MST): dropped now, the run need not stop at it.
    for (;;) {  // ends at the one just deferred, if not before
      const Entry& first = deferred_[deferred_head_];
      if (slots_[first.slot].generation == first.generation) break;
      ++deferred_head_;
    }
    stop_ = std::min(until_, deferred_[deferred_head_].when - 1);
    compact_deferred_if_due();
  }
  // arm_owned(owned, when, action) for an event whose action would change nothing while a
  // condition of its owner holds (INT_TEND raised with its flag latched): it takes its
  // order now and no queue entry. Once the run has passed its place (held_passed()) it
  // counts as run. The owner calls queue_held() the moment the condition ends: ahead still,
  // the event is queued where arm_owned() would have put it. A move to its time queues it
  // first, as a deferred event. Same rules as arm_owned(); cancel_owned() and disown() take
  // it as any other, move_owned() queues it. owned_pending() holds until it is queued or
  // cancelled, also once passed (pending_count() leaves a passed one out).
  // Inline: a ring holds one at every telegram sent and at every end marker.
  void hold_owned(OwnedSlot owned, Time when, Action action) {
    if (when < now_ || owned_pending(owned)) [[unlikely]]
      refuse_arm("Scheduler::hold_owned", owned, when);
    Slot& slot = slots_[owned];
    slot.generation = next_generation();  // odd: live
    slot.when = when;
    const std::uint32_t flags = slot.next_free;
    slot.action = action;
    if ((flags & kListed) == 0) [[unlikely]]  // the slot's first hold
      held_.push_back(owned);
    slot.next_free = (flags & ~kLazy) | kHeld | kListed;
  }
  // cancel_owned() and hold_owned() with the slot's action in one, for an owner holding its
  // event again and again (INT_TEND at every telegram sent). Inline: after the slot's first
  // hold, the cancel and the pending test come down to a new generation.
  void hold_owned_anew(OwnedSlot owned, Time when) {
    Slot& slot = slots_[owned];
    const std::uint32_t flags = slot.next_free;
    if (when < now_ || (flags & kListed) == 0) [[unlikely]] {
      cancel_owned(owned);
      return hold_owned(owned, when, slot.action);  // refuses a past `when`
    }
    slot.generation = next_generation();  // odd: live (an earlier event's entry no longer matches)
    slot.when = when;
    slot.next_free = (flags & ~kLazy) | kHeld;
  }
  // hold_owned() for an owner that knows its event's time only by working it out (a list's
  // end marker at its step of the cycle counter): the event takes its order now, and
  // `resolve(context)` (the slot's context) gives its time when something asks for it: the
  // time hold_owned() would have been given now, or kUnheld if the event was over already
  // (it never runs). The owner keeps that answer unchanged, or asks settle_held() before
  // changing it. A slot keeps the `resolve` of its first lazy hold. Same rules as
  // hold_owned() otherwise. Inline: nothing is worked out.
  static constexpr Time kUnheld = std::numeric_limits<Time>::max();
  using Resolve = Time (*)(void* context);
  void hold_owned_lazily(OwnedSlot owned, Action action, Resolve resolve) {
    if (owned_pending(owned)) [[unlikely]]
      refuse_arm("Scheduler::hold_owned_lazily", owned, now_);
    hold_idle_owned_lazily(owned, action, resolve);
  }
  // hold_owned_lazily() for a caller that knows the event is not pending (as
  // arm_owned_idle()): not tested (asserted in debug builds).
  void hold_idle_owned_lazily(OwnedSlot owned, Action action, Resolve resolve) {
    assert(!owned_pending(owned));
    assert(resolver_is(owned, resolve));  // a slot keeps the resolve of its first lazy hold
    Slot& slot = slots_[owned];
    slot.generation = next_generation();  // odd: live
    const std::uint32_t flags = slot.next_free;
    slot.action = action;
    if ((flags & (kListed | kResolver)) != (kListed | kResolver)) [[unlikely]]
      list_resolver(owned, resolve);
    slot.next_free = flags | kHeld | kListed | kResolver | kLazy;
  }
  // Works out the time of a lazily held event now (nothing if it is not lazily held).
  void settle_held(OwnedSlot owned) { settle_lazy(owned); }
  // Whether the run has passed the held event's place: it is before now, or now and
  // before the event running (all of now once run_until() is done).
  bool held_passed(OwnedSlot owned) const { return passed_or_over(owned); }
  // Queues the held event where arm_owned() at its hold would have put it, if it is still
  // ahead; a passed one is cancelled (it has run). Nothing if it is not held.
  void queue_held(OwnedSlot owned);
  // Moves the pending owned event to `when` as move() moves an event: it then runs after
  // the events already due at `when`. Throws std::invalid_argument if `when` is in the past,
  // std::logic_error if the event is not pending.
  void move_owned(OwnedSlot owned, Time when);
  // Gives the slot back (cancelled if pending): the owner is done with it.
  void disown(OwnedSlot owned);
  bool owned_pending(OwnedSlot owned) const { return slots_[owned].generation % 2 == 1; }
  // The pending owned event's generation: its place in the order of scheduling (a move
  // keeps it).
  Generation owned_generation(OwnedSlot owned) const { return slots_[owned].generation; }
  // Forgets the owned event if it is pending (its queue entry no longer matches).
  void cancel_owned(OwnedSlot owned) {
    if (owned_pending(owned)) ++slots_[owned].generation;
  }

  // Forgets a pending event. Returns false if it already ran or was cancelled.
  // Inline: most calls name an event that already ran.
  bool cancel(EventId id) {
    if (live_slot(id) == nullptr) return false;
    const std::uint32_t index = id.slot;
    // An action's slot holds no callback to release.
    if (slots_[index].action != nullptr) {
      free_slot(index);
    } else {
      release(index);
    }
    return true;
  }
  bool pending(EventId id) const { return live_slot(id) != nullptr; }
  // When a pending event runs; nullopt once it ran or was cancelled.
  std::optional<Time> when(EventId id) const {
    const Slot* slot = live_slot(id);
    if (slot == nullptr) return std::nullopt;
    return slot->when;
  }
  // Moves a pending event to `when`, keeping its id: it then runs after the events
  // already due at `when`, as if scheduled anew. Throws std::invalid_argument if `when`
  // is in the past; returns false (moving nothing) when the event is not pending.
  bool move(EventId id, Time when);
  // Counts the live slots: for tests and checks, not the event loop (which keeps no count).
  std::size_t pending_count() const;

  // Runs every event due at or before `until`, then sets the clock to `until`.
  // Throws std::invalid_argument if `until` is in the past.
  void run_until(Time until);
  // Runs the earliest pending event, if any. Returns false when none is pending.
  bool step();
  // Time of the earliest pending event; nullopt when none is pending. Lets a caller run
  // events one by one up to a time (e.g. a fuzzer bounding the work per input).
  std::optional<Time> next_time();

 private:
  // Events live in reusable slots (no allocation per event once the vectors have grown).
  // A slot's generation is odd while it holds an event: each event scheduled takes the next
  // odd number of one count (next_generation()), and a slot's goes up by one (even) when
  // its event runs or is cancelled; an EventId is that odd generation and the slot's index,
  // so a stale id never matches a reused slot (generations are not reused). The queue
  // holds only {time, slot, generation}, sorted by time; an event goes in after every entry
  // of its time, so same-time events keep their scheduling order. A deferred event, queued
  // later, finds its place among them by generation: the generations say the order in which
  // events were scheduled (earlier(); a moved event keeps its generation, so a move first
  // queues the deferred events due at its new time). A cancelled event's entry is dropped
  // when it comes to the front (its generation no longer matches).
  // 64 bytes: a slot's address is its index shifted, one instruction less at every look-up
  // (the callbacks, rare, are kept apart to fit).
  struct alignas(64) Slot {
    // An owned slot's action, or an at() event's; null: callbacks_ holds the at() event's.
    Action action = nullptr;
    void* context = nullptr;
    Time when = 0;
    Generation generation = 2;  // even: free; never 0, which EventId{} would match
    // Free list link: index + 1, 0 ends the list. An owned slot (never on the list):
    // kOwned and its flags (kHeld, kListed).
    std::uint32_t next_free = 0;
  };
  static_assert(sizeof(Slot) == 64);
  static constexpr std::uint32_t kOwned = 0x8000'0000u;
  // An owned slot held (hold_owned()) and neither armed nor queued since: pending while its
  // generation is odd. kListed: the slot is in held_ (from its first hold on).
  static constexpr std::uint32_t kHeld = 0x4000'0000u;
  static constexpr std::uint32_t kListed = 0x2000'0000u;
  // kLazy: held by hold_owned_lazily(), its `when` not worked out yet. kResolver: the slot
  // is in resolvers_ (from its first lazy hold on).
  static constexpr std::uint32_t kLazy = 0x1000'0000u;
  static constexpr std::uint32_t kResolver = 0x0800'0000u;
  struct Entry {
    Time when;
    std::uint32_t slot;
    Generation generation;
  };

  // A held event's place passed by the run (held_passed()).
  bool passed(Time when, Generation generation) const {
    return when < now_ || (when == now_ && !earlier(running_, generation));
  }
  bool passed(const Slot& slot) const { return passed(slot.when, slot.generation); }
  // The event of `slot` is held now (pending, and held since it was last armed).
  static bool held(const Slot& slot) {
    return (slot.next_free & (kOwned | kHeld)) == (kOwned | kHeld) && slot.generation % 2 == 1;
  }
  // A held slot's time, worked out if it is lazily held (kUnheld: it never runs).
  Time held_when(std::uint32_t index) const;
  // passed() for a held slot, lazily held or not (one that never runs has passed).
  bool passed_or_over(std::uint32_t index) const {
    const Time when = held_when(index);
    return when == kUnheld || passed(when, slots_[index].generation);
  }
  // A lazily held slot's time worked out and kept (one that never runs is cancelled).
  void settle_lazy(std::uint32_t index);
  void list_resolver(OwnedSlot owned, Resolve resolve);
  bool resolver_is(OwnedSlot owned, Resolve resolve) const;  // or none listed yet
  // Queues the held event of `index`, ahead still, in its place.
  void queue_held_slot(std::uint32_t index);
  // Queues the held events due at `when` and ahead, each in its place (before a move there).
  void queue_held_at(Time when);
  // Queues the held events ahead due at or before `next`, each in its place; true if it
  // queued any. For step() and next_time(), which see them as run_until() runs them.
  bool queue_held_through(Time next);
  // The generation of an event scheduled now (odd; 64 bits: never used up).
  Generation next_generation() { return generation_ += 2; }
  // An owned slot armed (queued, deferred or not) for `when`: its new generation, the order
  // it takes now; no longer held.
  Generation take_order(Slot& slot, Time when) {
    slot.when = when;
    slot.next_free &= ~(kHeld | kLazy);
    return slot.generation = next_generation();  // odd: live
  }
  // Whether the event of generation `a` was scheduled before that of `b`.
  static bool earlier(Generation a, Generation b) { return a < b; }
  [[noreturn]] void refuse_past(const char* what, Time when) const;
  [[noreturn]] void refuse_past_or_null(const char* what, Time when) const;
  // arm_owned() refused: `when` in the past, or the owned event pending already.
  [[noreturn, gnu::cold]] void refuse_arm(const char* what, OwnedSlot owned, Time when) const;
  // A free slot's index (the slot is still on the free list).
  std::uint32_t free_slot_index() { return free_head_ != 0 ? free_head_ - 1 : new_slot(); }
  std::uint32_t new_slot();
  // Takes slot `index` for an event at `when` and queues it; returns its EventId.
  EventId take_slot(std::uint32_t index, Time when) {
    Slot& slot = slots_[index];
    free_head_ = slot.next_free;
    const Generation generation = slot.generation = next_generation();  // odd: live
    slot.when = when;
    insert(when, index, generation);
    return EventId{generation, index};
  }
  void free_slot(std::uint32_t index) {
    Slot& slot = slots_[index];
    ++slot.generation;  // even: stale ids and queue entries no longer match
    slot.next_free = free_head_;
    free_head_ = index + 1;
  }
  void release(std::uint32_t index);             // cancels a live slot
  void requeue(std::uint32_t index, Time when);  // a pending event's entry, to `when`
  const Slot* live_slot(EventId id) const {
    if (id.slot >= slots_.size()) return nullptr;
    const Slot& slot = slots_[id.slot];
    return slot.generation == id.generation ? &slot : nullptr;
  }
  // A run of entries sorted by `when`, the earliest first: [head, tail) in `buffer`, which
  // is only storage (its size is the capacity). With a couple of dozen entries a sorted
  // array beats a heap: the front is taken in O(1), and a new entry is placed by binary
  // search and moves the shorter side. Pointers, not indices: the run loop and the inline
  // insert take an entry without scaling an index (a few instructions an event).
  struct SortedRun {
    std::vector<Entry> buffer;
    Entry* head = nullptr;
    Entry* tail = nullptr;
    Entry* end = nullptr;  // buffer.data() + buffer.size()

    // insert() walks to an entry's place from the front when it goes at most this far in.
    static constexpr std::size_t kWalk = 8;

    bool empty() const { return head == tail; }
    std::size_t head_index() const { return static_cast<std::size_t>(head - buffer.data()); }
    std::size_t tail_index() const { return static_cast<std::size_t>(tail - buffer.data()); }
    // The run is buffer[h, t) (after the buffer changed, or to set it anew).
    void place(std::size_t h, std::size_t t) {
      Entry* const data = buffer.data();
      head = data + h;
      tail = data + t;
      end = data + buffer.size();
    }
    void insert(const Entry& entry);
    void insert_indexed(const Entry& entry, std::size_t& head, std::size_t& tail);
    // A deferred event's entry: after the entries of its time scheduled before it.
    void insert_deferred(const Entry& entry);
    void remove(Time when, std::uint32_t slot, Generation generation);
    void make_room();
  };
  // The entries due after near_limit_, in the order they were queued (far_ below).
  struct LaterEntries {
    std::vector<Entry> entries;
    // No later than the earliest live entry (a cancelled one's may be earlier).
    Time earliest = std::numeric_limits<Time>::max();

    bool empty() const { return entries.empty(); }
    // Always inline (in insert(), itself inline in report events): a call saved six
    // registers for the growth it mostly does not need, so that is out of line.
    [[gnu::always_inline]] void push_back(const Entry& entry) {
      if (entries.size() == entries.capacity()) [[unlikely]] {
        grow_push(entry);
      } else {
        entries.push_back(entry);
      }
      earliest = std::min(earliest, entry.when);
    }
    [[gnu::noinline]] void grow_push(const Entry& entry) { entries.push_back(entry); }
    void remove(std::uint32_t slot, Generation generation);
    void insert_deferred(const Entry& entry);  // as SortedRun's, in scheduling order
  };

  // The first queue entry of a pending event, dropping those of cancelled ones; null when
  // nothing is pending. Deferred and held events due by then are queued first.
  const Entry* front() {
    for (;;) {
      const Entry* first = nullptr;
      for (; near_.head != near_.tail; ++near_.head) {
        const Entry& entry = *near_.head;
        if (slots_[entry.slot].generation == entry.generation) {
          first = &entry;
          break;
        }
      }
      if (first == nullptr && !far_.empty()) {
        refill();
        continue;
      }
      const Time next = first != nullptr ? first->when : std::numeric_limits<Time>::max();
      if (!held_.empty() && queue_held_through(next)) continue;
      if (!queue_deferred(next, std::numeric_limits<Time>::max())) return first;
    }
  }
  // Deferred events: deferred_[deferred_head_, end), sorted by time (those of one time in
  // the order deferred); cancelled ones are dropped as they come to the front. run_until()
  // stops at stop_, before until_ and the earliest deferred time, to queue them.
  bool deferred_waiting() const { return deferred_head_ != deferred_.size(); }
  // Queues the deferred events due at or before `next` and `until`, each in its place;
  // true if it queued any. Then sets stop_.
  bool queue_deferred(Time next, Time until);
  void queue_deferred_at(Time when);  // those due exactly then (before a move to `when`)
  void place_deferred(const Entry& entry);
  void defer_owned_slowly(OwnedSlot owned, Time when, Action action);
  // Drops the deferred_ entries before deferred_head_, once they are at least half of them
  // and some dozens: not at every call.
  static constexpr std::size_t kDeferredCompacted = 32;
  void compact_deferred_if_due() {
    if (deferred_head_ >= kDeferredCompacted && deferred_head_ * 2 >= deferred_.size()) [[unlikely]]
      compact_deferred();
  }
  void compact_deferred();
  void set_stop();
  void refill();
  void sort_near(std::size_t sorted, std::size_t n);  // refill()'s entries, by time
  static constexpr int kMergedRuns = 8;  // runs merged one by one; more: std::stable_sort
  // Inline: most new entries go at the back of near_ when it has room, and most of the
  // others only a few places behind its front (few entries are due sooner): they walk there
  // from the front, moving those few one place towards the entries that have run. An entry
  // due later goes at the back of far_, which is kept in scheduling order, not sorted.
  [[gnu::always_inline]] void insert(Time when, std::uint32_t slot, Generation generation) {
    if (when > near_limit_) [[unlikely]]
      return far_.push_back(Entry{when, slot, generation});
    SortedRun& run = near_;
    if (run.tail == run.head || when >= run.tail[-1].when) {
      if (run.tail != run.end) {
        *run.tail++ = Entry{when, slot, generation};
        return;
      }
    } else if (run.head != run.buffer.data() &&
               (run.tail - run.head <= static_cast<std::ptrdiff_t>(SortedRun::kWalk) ||
                when < run.head[SortedRun::kWalk].when)) {
      Entry* at = run.head;
      for (; at->when <= when; ++at) at[-1] = *at;
      at[-1] = Entry{when, slot, generation};
      --run.head;
      return;
    }
    run.insert(Entry{when, slot, generation});
  }
  // insert() at now, out of line: arm_owned_now()'s rare case (inline, it took registers).
  [[gnu::noinline]] void insert_now(std::uint32_t slot, Generation generation);
  void run(const Entry& entry);  // takes `entry` off the front and runs its event
  [[gnu::noinline]] void run_unowned(std::uint32_t index);  // run()'s at() events
  void run_callback(std::uint32_t index);

  Time now_ = 0;
  // Entries due at or before near_limit_ are in near_, the others in far_. Most events
  // are due soon and land at or near the back of the short near_ run; the few due much
  // later (more than kHorizon ahead) wait in far_ and do not make every placement move
  // them. When near_ runs empty, the limit moves to kHorizon - 1 after the earliest far
  // entry and the entries up to it move over, sorted by time (a stable sort: same-time
  // entries in the order they were queued). Same-time entries are always in one of the
  // two, so they keep their order. far_ is not sorted: with hundreds of later events (a
  // ring of 254 slaves) placing each in order moved half of them.
  // Only a matter of speed, never of order. 160 µs measured best on the 8-slave ring of
  // bench/ring_bench.cpp (250 µs cycle): 16 µs and 1 ms were both slower.
  static constexpr Time kHorizon = 160 * kMicrosecond;
  SortedRun near_;
  LaterEntries far_;
  std::vector<Entry> scratch_;  // sort_near()'s (swapped with near_'s buffer)
  Time near_limit_ = -1;
  Generation generation_ = 1;  // the last handed out
  // The generation of the event running or last run; generation_ once run_until() is done
  // (all events of now have run).
  Generation running_ = 1;
  std::vector<std::uint32_t> held_;  // the owned slots with kListed
  struct Resolver {
    std::uint32_t slot;
    Resolve resolve;
  };
  std::vector<Resolver> resolvers_;  // the owned slots with kResolver
  std::vector<Entry> deferred_;
  std::size_t deferred_head_ = 0;
  Time deferred_last_ = std::numeric_limits<Time>::min();  // no deferred_ entry is later
  Time until_ = std::numeric_limits<Time>::max();          // run_until()'s, while it runs
  Time stop_ = std::numeric_limits<Time>::max();
  std::vector<Slot> slots_;
  std::vector<Callback> callbacks_;  // at() events' callbacks, by slot (grown as needed)
  std::uint32_t free_head_ = 0;      // index + 1 of the first free slot, 0: none
};

}  // namespace sercon::sim

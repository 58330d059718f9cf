#include "sercon/sim/scheduler.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <utility>

namespace sercon::sim {
namespace {

[[noreturn, gnu::cold, gnu::noinline]] void throw_past(const char* what, Time when, Time now) {
  throw std::invalid_argument(std::string(what) + ": time " + std::to_string(when) +
                              " ps is before now (" + std::to_string(now) + " ps)");
}

}  // namespace

std::uint32_t Scheduler::new_slot() {
  slots_.emplace_back();
  return static_cast<std::uint32_t>(slots_.size() - 1);
}

std::uint32_t Scheduler::take_slot(Time when) {
  if (when < now_) throw_past("Scheduler::at", when, now_);
  std::uint32_t index;
  if (free_head_ != 0) {
    index = free_head_ - 1;
    free_head_ = slots_[index].next_free;
  } else {
    index = new_slot();
  }
  Slot& slot = slots_[index];
  slot.live = true;
  ++live_count_;
  insert(Entry{when, index, slot.generation});
  return index;
}

// The queue is full: drop the entries that have run when they are at least half of it,
// otherwise grow.
void Scheduler::make_room() {
  if (head_ * 2 >= queue_.size()) {
    queue_.erase(queue_.begin(), queue_.begin() + static_cast<std::ptrdiff_t>(head_));
    head_ = 0;
  } else {
    queue_.reserve(queue_.capacity() * 2);
  }
}

// After every entry at or before `when`: same-time events run in scheduling order.
void Scheduler::insert(const Entry& entry) {
  if (queue_empty()) {
    queue_.clear();
    head_ = 0;
    queue_.push_back(entry);
    return;
  }
  if (entry.when >= queue_.back().when) {
    if (queue_.size() == queue_.capacity()) make_room();
    queue_.push_back(entry);
    return;
  }
  Entry* first = queue_.data() + head_;
  Entry* last = queue_.data() + queue_.size();
  Entry* at = std::upper_bound(first, last, entry.when,
                               [](Time when, const Entry& e) { return when < e.when; });
  // Move the shorter side: the entries before `at` one place towards those that have
  // run, or those from `at` on one place back.
  if (head_ > 0 && at - first <= last - at) {
    std::move(first, at, first - 1);
    at[-1] = entry;
    --head_;
    return;
  }
  if (queue_.size() == queue_.capacity()) {
    const std::ptrdiff_t offset = at - queue_.data();
    const std::size_t head = head_;
    make_room();
    at = queue_.data() + offset - (head - head_);
  }
  queue_.push_back(queue_.back());
  last = queue_.data() + queue_.size() - 1;
  std::move_backward(at, last - 1, last);
  *at = entry;
}

Scheduler::EventId Scheduler::at(Time when, Callback callback) {
  const std::uint32_t index = take_slot(when);
  Slot& slot = slots_[index];
  slot.action = nullptr;
  slot.callback = std::move(callback);
  return EventId{std::uint64_t{slot.generation} << 32 | (index + 1u)};
}

Scheduler::EventId Scheduler::at(Time when, Action action, void* context) {
  const std::uint32_t index = take_slot(when);
  Slot& slot = slots_[index];
  slot.action = action;
  slot.context = context;
  return EventId{std::uint64_t{slot.generation} << 32 | (index + 1u)};
}

void Scheduler::release(std::uint32_t index) {
  slots_[index].callback = nullptr;  // release what it captured now
  free_slot(index);
}

bool Scheduler::run_next_due(Time until) {
  drop_dead_fronts();
  if (queue_empty() || queue_[head_].when > until) return false;
  const Entry next = queue_[head_++];
  Slot& slot = slots_[next.slot];
  now_ = next.when;
  // Take the event out before running it: it may schedule others (slots_ may grow).
  if (slot.action != nullptr) {
    const Action action = slot.action;
    void* const context = slot.context;
    free_slot(next.slot);
    action(context);
  } else {
    Callback callback = std::move(slot.callback);
    slot.callback = nullptr;
    free_slot(next.slot);
    callback();
  }
  return true;
}

void Scheduler::run_until(Time until) {
  if (until < now_) throw_past("Scheduler::run_until", until, now_);
  while (run_next_due(until)) {
  }
  now_ = until;
}

bool Scheduler::step() {
  drop_dead_fronts();
  if (queue_empty()) return false;
  return run_next_due(queue_[head_].when);
}

std::optional<Time> Scheduler::next_time() {
  drop_dead_fronts();
  if (queue_empty()) return std::nullopt;
  return queue_[head_].when;
}

}  // namespace sercon::sim

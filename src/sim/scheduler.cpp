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

Scheduler::Slot& Scheduler::take_slot(Time when) {
  if (when < now_) throw_past("Scheduler::at", when, now_);
  std::uint32_t index;
  if (free_head_ != 0) {
    index = free_head_ - 1;
    free_head_ = slots_[index].next_free;
  } else {
    index = static_cast<std::uint32_t>(slots_.size());
    slots_.emplace_back();
  }
  Slot& slot = slots_[index];
  ++slot.generation;  // odd: live
  slot.when = when;
  ++live_count_;
  insert(when, index, slot.generation);
  return slot;
}

// The queue's storage is full: drop the entries that have run when they are at least
// half of it, otherwise grow.
void Scheduler::make_room() {
  if (head_ > 0 && head_ * 2 >= tail_) {
    std::copy(queue_.begin() + static_cast<std::ptrdiff_t>(head_),
              queue_.begin() + static_cast<std::ptrdiff_t>(tail_), queue_.begin());
    tail_ -= head_;
    head_ = 0;
  } else {
    queue_.resize(std::max<std::size_t>(16, queue_.size() * 2));
  }
}

// After every entry at or before `when`: same-time events run in scheduling order.
void Scheduler::insert(Time when, std::uint32_t slot, std::uint32_t generation) {
  const Entry entry{when, slot, generation};
  if (head_ == tail_) {
    head_ = tail_ = 0;
  } else if (when < queue_[tail_ - 1].when) {
    Entry* const first = queue_.data() + head_;
    Entry* const last = queue_.data() + tail_;
    // Branch-free upper bound: the first entry later than `when` (one exists).
    Entry* base = first;
    for (std::size_t n = tail_ - head_; n > 1;) {
      const std::size_t half = n / 2;
      base = base[half].when <= when ? base + half : base;
      n -= half;
    }
    Entry* const at = base + (base->when <= when);
    // Move the shorter side: the entries before `at` one place towards those that have
    // run, or those from `at` on one place back.
    if (head_ > 0 && at - first <= last - at) {
      std::copy(first, at, first - 1);
      at[-1] = entry;
      --head_;
      return;
    }
    if (tail_ == queue_.size()) {
      const std::size_t offset = static_cast<std::size_t>(at - first);
      make_room();
      Entry* const moved = queue_.data() + head_ + offset;
      std::copy_backward(moved, queue_.data() + tail_, queue_.data() + tail_ + 1);
      *moved = entry;
    } else {
      std::copy_backward(at, last, last + 1);
      *at = entry;
    }
    ++tail_;
    return;
  }
  if (tail_ == queue_.size()) make_room();
  queue_[tail_++] = entry;
}

Scheduler::EventId Scheduler::at(Time when, Callback callback) {
  Slot& slot = take_slot(when);
  slot.action = nullptr;
  slot.callback = std::move(callback);
  const auto index = static_cast<std::uint32_t>(&slot - slots_.data());
  return EventId{std::uint64_t{slot.generation} << 32 | (index + 1u)};
}

Scheduler::EventId Scheduler::at(Time when, Action action, void* context) {
  Slot& slot = take_slot(when);
  slot.action = action;
  slot.context = context;
  const auto index = static_cast<std::uint32_t>(&slot - slots_.data());
  return EventId{std::uint64_t{slot.generation} << 32 | (index + 1u)};
}

// Takes a pending event's entry out of the queue (it is there: live entries are never
// passed over).
void Scheduler::remove(Time when, std::uint32_t slot) {
  Entry* const last = queue_.data() + tail_;
  Entry* at = std::lower_bound(queue_.data() + head_, last, when,
                               [](const Entry& e, Time t) { return e.when < t; });
  while (at->slot != slot) ++at;
  std::copy(at + 1, last, at);
  --tail_;
}

bool Scheduler::move(EventId id, Time when) {
  if (when < now_) throw_past("Scheduler::move", when, now_);
  if (live_slot(id) == nullptr) return false;
  const auto index = static_cast<std::uint32_t>((id.value & 0xFFFF'FFFFu) - 1);
  Slot& slot = slots_[index];
  remove(slot.when, index);
  slot.when = when;
  insert(when, index, slot.generation);
  return true;
}

void Scheduler::release(std::uint32_t index) {
  slots_[index].callback = nullptr;  // release what it captured now
  free_slot(index);
}

void Scheduler::run(const Entry& entry) {
  ++head_;
  now_ = entry.when;
  const std::uint32_t index = entry.slot;
  Slot& slot = slots_[index];
  // Take the event out before running it: it may schedule others (slots_ may grow).
  if (slot.action != nullptr) {
    const Action action = slot.action;
    void* const context = slot.context;
    free_slot(index);
    action(context);
  } else {
    Callback callback = std::move(slot.callback);
    slot.callback = nullptr;
    free_slot(index);
    callback();
  }
}

void Scheduler::run_until(Time until) {
  if (until < now_) throw_past("Scheduler::run_until", until, now_);
  for (const Entry* next = front(); next != nullptr && next->when <= until; next = front()) {
    run(*next);
  }
  now_ = until;
}

bool Scheduler::step() {
  const Entry* next = front();
  if (next == nullptr) return false;
  run(*next);
  return true;
}

std::optional<Time> Scheduler::next_time() {
  const Entry* next = front();
  if (next == nullptr) return std::nullopt;
  return next->when;
}

}  // namespace sercon::sim

#include "sercon/sim/scheduler.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <utility>

namespace sercon::sim {
namespace {

// Min-heap order: earlier time first, then earlier scheduling.
struct Later {
  template <typename E>
  bool operator()(const E& a, const E& b) const {
    return a.when != b.when ? a.when > b.when : a.order > b.order;
  }
};

}  // namespace

std::uint32_t Scheduler::take_slot(Time when) {
  if (when < now_) {
    throw std::invalid_argument("Scheduler::at: time " + std::to_string(when) +
                                " ps is before now (" + std::to_string(now_) + " ps)");
  }
  std::uint32_t index;
  if (!free_slots_.empty()) {
    index = free_slots_.back();
    free_slots_.pop_back();
  } else {
    index = static_cast<std::uint32_t>(slots_.size());
    slots_.emplace_back();
  }
  Slot& slot = slots_[index];
  slot.live = true;
  ++live_count_;
  heap_.push_back(Entry{when, next_order_++, index, slot.generation});
  std::push_heap(heap_.begin(), heap_.end(), Later{});
  return index;
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

void Scheduler::free_slot(std::uint32_t index) {
  Slot& slot = slots_[index];
  slot.live = false;
  ++slot.generation;  // stale ids and heap entries no longer match
  --live_count_;
  free_slots_.push_back(index);
}

void Scheduler::release(std::uint32_t index) {
  slots_[index].callback = nullptr;  // release what it captured now
  free_slot(index);
}

bool Scheduler::top_is_live() const {
  const Entry& top = heap_.front();
  const Slot& slot = slots_[top.slot];
  return slot.live && slot.generation == top.generation;
}

void Scheduler::pop_top() {
  std::pop_heap(heap_.begin(), heap_.end(), Later{});
  heap_.pop_back();
}

void Scheduler::drop_dead_tops() {
  while (!heap_.empty() && !top_is_live()) pop_top();
}

bool Scheduler::run_next_due(Time until) {
  drop_dead_tops();
  if (heap_.empty() || heap_.front().when > until) return false;
  const Entry next = heap_.front();
  pop_top();
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
  if (until < now_) {
    throw std::invalid_argument("Scheduler::run_until: time " + std::to_string(until) +
                                " ps is before now (" + std::to_string(now_) + " ps)");
  }
  while (run_next_due(until)) {
  }
  now_ = until;
}

bool Scheduler::step() {
  drop_dead_tops();
  if (heap_.empty()) return false;
  return run_next_due(heap_.front().when);
}

std::optional<Time> Scheduler::next_time() {
  drop_dead_tops();
  if (heap_.empty()) return std::nullopt;
  return heap_.front().when;
}

}  // namespace sercon::sim

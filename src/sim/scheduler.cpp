#include "sercon/sim/scheduler.hpp"

#include <stdexcept>
#include <string>

namespace sercon::sim {

Scheduler::EventId Scheduler::at(Time when, Callback callback) {
  if (when < now_) {
    throw std::invalid_argument("Scheduler::at: time " + std::to_string(when) +
                                " ps is before now (" + std::to_string(now_) + " ps)");
  }
  const std::uint64_t id = next_id_++;
  queue_.push(Entry{when, id});
  callbacks_.emplace(id, std::move(callback));
  return EventId{id};
}

bool Scheduler::cancel(EventId id) { return callbacks_.erase(id.value) > 0; }

bool Scheduler::run_next_due(Time until) {
  while (!queue_.empty()) {
    const Entry next = queue_.top();
    if (next.when > until) return false;
    queue_.pop();
    auto found = callbacks_.find(next.id);
    if (found == callbacks_.end()) continue;  // cancelled
    Callback callback = std::move(found->second);
    callbacks_.erase(found);
    now_ = next.when;
    callback();
    return true;
  }
  return false;
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
  while (!queue_.empty() && !callbacks_.contains(queue_.top().id)) queue_.pop();
  if (queue_.empty()) return false;
  return run_next_due(queue_.top().when);
}

std::optional<Time> Scheduler::next_time() {
  while (!queue_.empty() && !callbacks_.contains(queue_.top().id)) queue_.pop();
  if (queue_.empty()) return std::nullopt;
  return queue_.top().when;
}

}  // namespace sercon::sim

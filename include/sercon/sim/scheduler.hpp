// A discrete-event scheduler. Events at the same time run in the order they were
// scheduled, so a scenario replays identically (brief: determinism).
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <queue>
#include <unordered_map>
#include <vector>

#include "sercon/sim/time.hpp"

namespace sercon::sim {

class Scheduler {
 public:
  using Callback = std::function<void()>;
  struct EventId {
    std::uint64_t value = 0;  // 0 never names an event
    friend bool operator==(EventId, EventId) = default;
  };

  Time now() const { return now_; }

  // Runs `callback` at absolute time `when`; throws std::invalid_argument if `when` is
  // in the past.
  EventId at(Time when, Callback callback);
  // Runs `callback` `delay` picoseconds from now (delay >= 0).
  EventId after(Time delay, Callback callback) { return at(now_ + delay, std::move(callback)); }

  // Forgets a pending event. Returns false if it already ran or was cancelled.
  bool cancel(EventId id);
  bool pending(EventId id) const { return callbacks_.contains(id.value); }
  std::size_t pending_count() const { return callbacks_.size(); }

  // Runs every event due at or before `until`, then sets the clock to `until`.
  // Throws std::invalid_argument if `until` is in the past.
  void run_until(Time until);
  // Runs the earliest pending event, if any. Returns false when none is pending.
  bool step();
  // Time of the earliest pending event; nullopt when none is pending. Lets a caller run
  // events one by one up to a time (e.g. a fuzzer bounding the work per input).
  std::optional<Time> next_time();

 private:
  struct Entry {
    Time when;
    std::uint64_t id;  // also the tie-breaker: lower id was scheduled first
    bool operator>(const Entry& other) const {
      return when != other.when ? when > other.when : id > other.id;
    }
  };
  bool run_next_due(Time until);

  Time now_ = 0;
  std::uint64_t next_id_ = 1;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<>> queue_;
  std::unordered_map<std::uint64_t, Callback> callbacks_;
};

}  // namespace sercon::sim

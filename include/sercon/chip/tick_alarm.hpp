// One scheduled callback at a tick of a divider (or at a given MCLK edge) that can be
// moved when the divider's period changes. Cancels itself when destroyed, so no event
// outlives the unit that owns it. The callback is the alarm's for good (each alarm of a
// unit always calls the same member), so arming it copies no function object.
#pragma once

#include <cstdint>
#include <functional>
#include <utility>

#include "sercon/chip/mclk_divider.hpp"
#include "sercon/sim/scheduler.hpp"

namespace sercon::chip {

class TickAlarm {
 public:
  TickAlarm(sim::Scheduler& scheduler, const MclkGrid& mclk, std::function<void()> callback)
      : scheduler_(scheduler), mclk_(mclk), callback_(std::move(callback)) {}
  ~TickAlarm() { cancel(); }
  TickAlarm(const TickAlarm&) = delete;
  TickAlarm& operator=(const TickAlarm&) = delete;

  // Calls the callback at tick `k` (>= 1) of `ticks`; replaces what was set before.
  void at_tick(const DividerTicks& ticks, std::int64_t k);
  // Calls the callback at MCLK edge `edge`; retime() leaves it where it is.
  void at_edge(Edge edge);
  // The divider's period changed at edge `changed_at`: move a tick alarm that is due
  // after that edge to its tick's new edge.
  void retime(const DividerTicks& ticks, Edge changed_at);
  void cancel();
  bool pending() const { return scheduler_.pending(event_); }
  sim::Time when() const { return when_; }  // meaningful while pending()

 private:
  void schedule(Edge edge);
  static void fire(void* alarm);  // the scheduler event (function + context)

  sim::Scheduler& scheduler_;
  const MclkGrid& mclk_;
  sim::Scheduler::EventId event_{};
  std::function<void()> callback_;
  std::int64_t tick_ = 0;  // 0: an edge alarm
  sim::Time when_ = 0;
};

}  // namespace sercon::chip

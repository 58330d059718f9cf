#include "sercon/chip/tick_alarm.hpp"

#include <algorithm>

namespace sercon::chip {

void TickAlarm::at_tick(const DividerTicks& ticks, std::int64_t k) {
  cancel();
  tick_ = std::max<std::int64_t>(k, 1);
  schedule(ticks.edge_of(tick_));
}

void TickAlarm::at_edge(Edge edge) {
  cancel();
  tick_ = 0;
  schedule(edge);
}

void TickAlarm::retime(const DividerTicks& ticks, Edge changed_at) {
  if (!pending() || tick_ == 0 || when_ <= mclk_.time_of(changed_at)) return;
  scheduler_.cancel(event_);
  schedule(ticks.edge_of(tick_));
}

void TickAlarm::cancel() {
  scheduler_.cancel(event_);
  event_ = {};
}

void TickAlarm::schedule(Edge edge) {
  // A tick is never in the past when set; the clamp is a guard, not a rule.
  when_ = std::max(mclk_.time_of(edge), scheduler_.now());
  event_ = scheduler_.at(when_, &TickAlarm::fire, this);
}

void TickAlarm::fire(void* alarm) {
  auto& a = *static_cast<TickAlarm*>(alarm);
  a.event_ = {};
  a.callback_();  // may arm the alarm again: that leaves callback_ as it is
}

}  // namespace sercon::chip

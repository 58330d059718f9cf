#include "sercon/chip/settled_line.hpp"

#include <stdexcept>
#include <string>

namespace sercon::chip {

SettledLine::~SettledLine() {
  for (const Change& c : queue_) scheduler_.cancel(c.event);
}

void SettledLine::line_condition(sim::Time at, LineCondition condition, sim::Time bit_period) {
  Change c;
  c.condition = condition;
  c.burst.start = at;
  c.burst.bit_period = bit_period;
  take(std::move(c));
}

void SettledLine::line_burst(const LineBurst& burst) {
  Change c;
  c.is_burst = true;
  c.burst = burst;
  take(std::move(c));
}

void SettledLine::take(Change change) {
  const sim::Time at = change.burst.start;
  if (at < scheduler_.now()) {
    throw std::invalid_argument("line: a change at " + std::to_string(at) + " ps is before now (" +
                                std::to_string(scheduler_.now()) + " ps)");
  }
  // The later word wins: what was announced for `at` or later is overtaken.
  while (!queue_.empty() && queue_.back().burst.start >= at) {
    scheduler_.cancel(queue_.back().event);
    queue_.pop_back();
  }
  if (at == scheduler_.now()) return pass_on(change);
  queue_.push_back(std::move(change));
  queue_.back().event = scheduler_.at(
      at, [](void* self) { static_cast<SettledLine*>(self)->due(); }, this);
}

void SettledLine::due() {
  const Change c = std::move(queue_.front());
  queue_.pop_front();
  pass_on(c);
}

void SettledLine::pass_on(const Change& c) {
  if (c.is_burst) return target_.line_burst(c.burst);
  target_.line_condition(c.burst.start, c.condition, c.burst.bit_period);
}

}  // namespace sercon::chip

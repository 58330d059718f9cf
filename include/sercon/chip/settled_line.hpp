// A line listener that hears each change at the moment it happens: it keeps the announced
// changes (line.hpp) in time order and passes each on to its target when its time comes,
// dropping those a later announcement supersedes. For listeners written for "now" (the
// RS-485 bus, which arbitrates drivers as they drive; recorders in tests): one scheduled
// event per change.
#pragma once

#include <deque>

#include "sercon/chip/line.hpp"
#include "sercon/sim/scheduler.hpp"

namespace sercon::chip {

class SettledLine final : public LineListener {
 public:
  SettledLine(sim::Scheduler& scheduler, LineListener& target)
      : scheduler_(scheduler), target_(target) {}
  ~SettledLine() override;
  SettledLine(const SettledLine&) = delete;
  SettledLine& operator=(const SettledLine&) = delete;

  // std::invalid_argument for a time before now.
  void line_condition(sim::Time at, LineCondition condition, sim::Time bit_period) override;
  void line_burst(const LineBurst& burst) override;

 private:
  struct Change {
    bool is_burst = false;
    LineCondition condition = LineCondition::Dark;
    LineBurst burst;  // for a condition: start = its time, bit_period = its period
    sim::Scheduler::EventId event;
  };
  void take(Change change);
  void pass_on(const Change& change);
  void due();  // the front of queue_ is due

  sim::Scheduler& scheduler_;
  LineListener& target_;
  std::deque<Change> queue_;  // announced, not yet due; in time order
};

}  // namespace sercon::chip

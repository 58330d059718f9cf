// A line listener between a line's source and its listener (a fibre's far end and a
// receiver, say): shows every change to `log` first, then passes it on unchanged.
#pragma once

#include <utility>

#include "sercon/chip/line.hpp"

namespace sercon::chip::testing {

template <class Log>
class LineTee final : public LineListener {
 public:
  template <class... LogArgs>
  explicit LineTee(LineListener& to, LogArgs&&... log_args)
      : log(std::forward<LogArgs>(log_args)...), to_(to) {}
  void line_condition(sim::Time at, LineCondition condition, sim::Time period) override {
    log.line_condition(at, condition, period);
    to_.line_condition(at, condition, period);
  }
  void line_burst(const LineBurst& burst) override {
    log.line_burst(burst);
    to_.line_burst(burst);
  }
  Log log;

 private:
  LineListener& to_;
};

}  // namespace sercon::chip::testing

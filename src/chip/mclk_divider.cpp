#include "sercon/chip/mclk_divider.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace sercon::chip {

MclkGrid::MclkGrid(sim::Time period) : period_(period) {
  if (period <= 0) {
    throw std::invalid_argument("MclkGrid: MCLK period must be > 0 ps, got " +
                                std::to_string(period));
  }
}

Edge MclkGrid::first_at_or_after(sim::Time t) const {
  if (t <= 0) return 0;
  return (t + period_ - 1) / period_;
}

Edge MclkGrid::last_at_or_before(sim::Time t) const {
  if (t < 0) return -1;
  return t / period_;
}

DividerTicks DividerTicks::started_at(Edge start, std::int64_t first_delay, std::int64_t period) {
  DividerTicks ticks;
  ticks.first_ = start + std::max<std::int64_t>(first_delay, 1);
  ticks.period_ = std::max<std::int64_t>(period, 1);
  return ticks;
}

std::int64_t DividerTicks::count_through(Edge edge) const {
  if (edge < first_) return base_;
  return base_ + (edge - first_) / period_ + 1;
}

void DividerTicks::change_period(Edge now, std::int64_t period) {
  const std::int64_t next = count_through(now) + 1;
  first_ = edge_of(next);
  base_ = next - 1;
  period_ = std::max<std::int64_t>(period, 1);
}

}  // namespace sercon::chip

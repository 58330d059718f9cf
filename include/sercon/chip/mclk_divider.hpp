// The MCLK grid and the MCLKDIV dividers derived from it (delta spec 2.11.1.2, 2.6.3).
// Every divider tick falls on an MCLK rising edge. Edge k is at floor(k * 1e12 / f_MCLK)
// ps from time 0 (as Chip::next_mclk_edge): exact for any frequency, with no drift, and
// k * period when the period is a whole number of picoseconds. Nothing is ticked: a
// divider is an anchor and a period, and tick times are computed.
#pragma once

#include <cstdint>

#include "sercon/sim/time.hpp"

namespace sercon::chip {

using Edge = std::int64_t;  // index of an MCLK rising edge

class MclkGrid {
 public:
  // std::invalid_argument unless 0 < hz <= 1e12.
  explicit MclkGrid(std::int64_t hz);
  // The grid of a period that is a whole number of picoseconds (1e12 % period == 0);
  // std::invalid_argument otherwise.
  static MclkGrid of_period(sim::Time period);

  std::int64_t hz() const { return hz_; }
  // The longest gap between two edges: 1e12 / f_MCLK rounded up. Edges are apart by it or
  // by one picosecond less.
  sim::Time period() const { return (sim::kSecond + hz_ - 1) / hz_; }
  sim::Time time_of(Edge edge) const;         // floor(edge * 1e12 / f_MCLK)
  Edge first_at_or_after(sim::Time t) const;  // 0 for t <= 0
  Edge last_at_or_before(sim::Time t) const;  // -1 for t < 0

 private:
  std::int64_t hz_;
};

// The ticks of one divider since its last restart. Tick k (k = 1, 2, ...) falls on edge
// first + (k - 1) * period. The hardware reloads MCLKDIV at each tick, so a new period
// takes effect after the tick that is pending when it is written.
class DividerTicks {
 public:
  DividerTicks() = default;
  // Restarted at edge `start`: first tick `first_delay` edges later, then one every
  // `period` edges. Both are taken as at least 1 (a divider cannot tick twice per edge).
  static DividerTicks started_at(Edge start, std::int64_t first_delay, std::int64_t period);

  std::int64_t period() const { return period_; }
  // Ticks at edges <= `edge`.
  std::int64_t count_through(Edge edge) const;
  // Edge of tick `k`; meaningful for ticks after the last period change.
  Edge edge_of(std::int64_t k) const { return first_ + (k - base_ - 1) * period_; }
  // MCLKDIV written, registered at edge `now`: ticks up to the first one after `now` keep
  // their edges, later ones are `period` apart.
  void change_period(Edge now, std::int64_t period);

 private:
  std::int64_t base_ = 0;  // ticks counted before `first_`
  Edge first_ = 1;         // edge of tick base_ + 1
  std::int64_t period_ = 1;
};

}  // namespace sercon::chip

// The MCLK grid and the MCLKDIV dividers derived from it (delta spec 2.11.1.2, 2.6.3).
// Every divider tick falls on an MCLK rising edge. Edge k is at floor(k * 1e12 / f_MCLK)
// ps from time 0 (as Chip::next_mclk_edge): exact for any frequency, with no drift, and
// k * period when the period is a whole number of picoseconds. Nothing is ticked: a
// divider is an anchor and a period, and tick times are computed.
//
// Arithmetic: with f / 1e12 reduced to a / b, edge k is at floor(k * b / a) and time t
// lies near edge t * a / b. Splitting k (or t) by a (or b) keeps every product below a * b,
// so when (a + 1) * b fits 64 bits (every f up to 18.4 MHz, every even f up to 73 MHz) the
// grid needs no 128-bit division; an exact period (a == 1: 16, 20, 25, 32, 40, 50, 64 MHz)
// needs no division (a multiply by its reciprocal). Other grids, and results outside 64 bits, take
// the 128-bit formula; both give identical results (MclkGrid.FastPathMatchesThe128BitFormula).
#pragma once

#include <algorithm>
#include <cstdint>

#include "sercon/sim/reciprocal.hpp"
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
  sim::Time period() const { return period_; }
  sim::Time time_of(Edge edge) const;         // floor(edge * 1e12 / f_MCLK)
  Edge first_at_or_after(sim::Time t) const;  // 0 for t <= 0
  Edge last_at_or_before(sim::Time t) const;  // -1 for t < 0
  // The `n`-th edge after the first at or after t: where a synchroniser of n flip-flops
  // takes up what came at t (a receiver's report, a slave's MST load, CYC_CLK).
  // 0 <= n <= kFewEdges on an exact grid (the usual one) takes one multiply for the division.
  static constexpr Edge kFewEdges = 64;
  sim::Time nth_edge_after(sim::Time t, Edge n) const {
    // 0 < t <= exact_limit_: the edge is within exact_edges_, at edge * b.
    if (exact_few(t, n)) return static_cast<sim::Time>(exact_nth_edge(t, n) * den_);
    return time_of(first_at_or_after(t) + n);
  }
  // On an exact grid, nth_edge_after(t, n) is (ceil(t / period()) + n) * period() for
  // 0 < t <= exact_limit() and 0 <= n <= kFewEdges; 0 for other grids.
  std::uint64_t exact_limit() const { return exact_limit_; }
  // The same edge's index and time (a slave's MST load edge: its cycle starts from it).
  struct EdgeAt {
    Edge edge;
    sim::Time time;
  };
  EdgeAt nth_edge_at(sim::Time t, Edge n) const {
    if (exact_few(t, n)) {
      const std::uint64_t edge = exact_nth_edge(t, n);
      return {static_cast<Edge>(edge), static_cast<sim::Time>(edge * den_)};
    }
    const Edge edge = first_at_or_after(t) + n;
    return {edge, time_of(edge)};
  }

 private:
  // floor(u / den_) and its remainder by a multiply with the reciprocal (sim::Reciprocal):
  // the edge is asked for at nearly every event, where a 64-bit division costs more time
  // than the rest of the question.
  struct QuotRem {
    std::uint64_t quot, rem;
  };
  // nth_edge_after's fast path: 0 < t <= exact_limit_, the edge within exact_edges_.
  bool exact_few(sim::Time t, Edge n) const {
    return static_cast<std::uint64_t>(t) - 1 < exact_limit_ && n >= 0 && n <= kFewEdges;
  }
  // The first edge at or after t, ceil(t / b), as floor((t + b - 1) / b): no remainder to
  // work out (t + b - 1 stays below 2^64: exact_limit_ is below 2^63); then n more.
  std::uint64_t exact_nth_edge(sim::Time t, Edge n) const {
    return by_den_.divide(static_cast<std::uint64_t>(t) + den_ - 1) + static_cast<std::uint64_t>(n);
  }
  QuotRem by_den(std::uint64_t u) const {
    const std::uint64_t q = by_den_.divide(u);
    return {q, u - q * den_};
  }
  // The 128-bit formulas, valid everywhere.
  sim::Time wide_time_of(Edge edge) const;
  Edge wide_first_at_or_after(sim::Time t) const;
  Edge wide_last_at_or_before(sim::Time t) const;

  std::int64_t hz_;
  sim::Time period_ = 0;       // worked out once: asked for every report time a receiver plans
  std::uint64_t num_ = 1;      // a: f_MCLK / gcd(f_MCLK, 1e12)
  std::uint64_t den_ = 1;      // b: 1e12 / gcd(f_MCLK, 1e12); the period when num_ == 1
  sim::Reciprocal by_den_{1};  // divides by b
  bool narrow_ = false;        // (a + 1) * b fits 64 bits: the split formulas apply
  // Edges 0..exact_edges_ are at edge * b exactly: a == 1 and the product fits (else 0:
  // edge 0 at 0 holds for every grid).
  std::uint64_t exact_edges_ = 0;
  // nth_edge_after's fast path holds for 0 < t <= exact_limit_ (0: never, not exact).
  std::uint64_t exact_limit_ = 0;
};

// Inline: the simulation asks for edges on nearly every event.
inline sim::Time MclkGrid::time_of(Edge edge) const {
  if (static_cast<std::uint64_t>(edge) <= exact_edges_) {
    return static_cast<sim::Time>(static_cast<std::uint64_t>(edge) * den_);
  }
  if (narrow_ && edge >= 0) {
    const auto k = static_cast<std::uint64_t>(edge);
    // floor(k * b / a) = (k / a) * b + (k % a) * b / a; (k % a) * b < a * b.
    const std::uint64_t whole = num_ == 1 ? k : k / num_;
    const std::uint64_t part = num_ == 1 ? 0 : (k % num_) * den_ / num_;
    std::uint64_t t;
    if (!__builtin_mul_overflow(whole, den_, &t) && !__builtin_add_overflow(t, part, &t) &&
        t <= static_cast<std::uint64_t>(INT64_MAX)) {
      return static_cast<sim::Time>(t);
    }
  }
  return wide_time_of(edge);
}

// The smallest k with k * b >= t * a: ceil(t * a / b) = (t / b) * a + ceil((t % b) * a / b).
inline Edge MclkGrid::first_at_or_after(sim::Time t) const {
  if (t <= 0) return 0;
  const auto u = static_cast<std::uint64_t>(t);
  if (num_ == 1) {  // narrow_ too
    const QuotRem d = by_den(u);
    return static_cast<Edge>(d.quot + (d.rem != 0));
  }
  if (!narrow_) return wide_first_at_or_after(t);
  const std::uint64_t q = u / den_;
  const std::uint64_t r = u % den_;
  return static_cast<Edge>(q * num_ + (r * num_ + den_ - 1) / den_);
}

// The largest k with floor(k * b / a) <= t, i.e. k * b < (t + 1) * a:
// floor(((t + 1) * a - 1) / b), which is floor(t / b) for an exact period.
inline Edge MclkGrid::last_at_or_before(sim::Time t) const {
  if (t < 0) return -1;
  const auto u = static_cast<std::uint64_t>(t);
  if (num_ == 1) return static_cast<Edge>(by_den(u).quot);  // narrow_ too
  if (!narrow_) return wide_last_at_or_before(t);
  // (t + 1) = q * b + r; t < 2^63, so t + 1 fits unsigned.
  const std::uint64_t q = (u + 1) / den_;
  const std::uint64_t r = (u + 1) % den_;
  if (r == 0) return static_cast<Edge>(q * num_ - 1);
  return static_cast<Edge>(q * num_ + (r * num_ - 1) / den_);
}

// The ticks of one divider since its last restart. Tick k (k = 1, 2, ...) falls on edge
// first + (k - 1) * period. The hardware reloads MCLKDIV at each tick, so a new period
// takes effect after the tick that is pending when it is written.
class DividerTicks {
 public:
  DividerTicks() = default;
  // Restarted at edge `start`: first tick `first_delay` edges later, then one every
  // `period` edges. Both are taken as at least 1 (a divider cannot tick twice per edge).
  // Inline: every cycle start of every chip restarts one.
  static DividerTicks started_at(Edge start, std::int64_t first_delay, std::int64_t period) {
    DividerTicks ticks;
    ticks.first_ = start + std::max<std::int64_t>(first_delay, 1);
    ticks.period_ = std::max<std::int64_t>(period, 1);
    return ticks;
  }

  std::int64_t period() const { return period_; }
  // Ticks counted before the last period change (0 after a restart): edge_of() holds for
  // the later ones.
  std::int64_t ticks_before_change() const { return base_; }
  // Ticks at edges <= `edge`. Inline: asked at every cycle start and cycle-time event.
  std::int64_t count_through(Edge edge) const {
    if (edge < first_) return base_;
    return base_ + (edge - first_) / period_ + 1;
  }
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

#include "sercon/chip/mclk_divider.hpp"

#include <algorithm>
#include <numeric>
#include <stdexcept>
#include <string>

namespace sercon::chip {

namespace {

// 128 bits: edge * 1e12 and t * f_MCLK overflow 64 bits after about 100 days of
// simulated time.
__extension__ typedef __int128 Wide;

// floor(n / d) for d > 0.
Wide floor_div(Wide n, Wide d) {
  const Wide q = n / d;
  return (n % d != 0 && n < 0) ? q - 1 : q;
}

}  // namespace

MclkGrid::MclkGrid(std::int64_t hz) : hz_(hz) {
  if (hz <= 0 || hz > sim::kSecond) {
    throw std::invalid_argument("MclkGrid: MCLK must be 1 Hz..1 THz, got " + std::to_string(hz) +
                                " Hz");
  }
  period_ = (sim::kSecond + hz - 1) / hz;
  const auto g = static_cast<std::uint64_t>(std::gcd(hz, sim::kSecond));
  num_ = static_cast<std::uint64_t>(hz) / g;
  den_ = static_cast<std::uint64_t>(sim::kSecond) / g;
  by_den_ = sim::Reciprocal(den_);
  std::uint64_t bound;
  narrow_ = !__builtin_mul_overflow(num_ + 1, den_, &bound);
  if (num_ == 1) {
    exact_edges_ = static_cast<std::uint64_t>(INT64_MAX) / den_;
    // t <= (exact_edges_ - kFewEdges - 1) * b: the first edge at or after t, plus kFewEdges,
    // is at most exact_edges_.
    exact_limit_ = (exact_edges_ - static_cast<std::uint64_t>(kFewEdges) - 1) * den_;
  }
}

MclkGrid MclkGrid::of_period(sim::Time period) {
  if (period <= 0 || sim::kSecond % period != 0) {
    throw std::invalid_argument("MclkGrid: " + std::to_string(period) +
                                " ps is not an exact MCLK period (1e12 % period != 0)");
  }
  return MclkGrid(sim::kSecond / period);
}

sim::Time MclkGrid::wide_time_of(Edge edge) const {
  return static_cast<sim::Time>(floor_div(Wide{edge} * sim::kSecond, hz_));
}

// The smallest k with floor(k * 1e12 / f) >= t, i.e. k * 1e12 >= t * f (t > 0).
Edge MclkGrid::wide_first_at_or_after(sim::Time t) const {
  return static_cast<Edge>(floor_div(Wide{t} * hz_ + sim::kSecond - 1, sim::kSecond));
}

// The largest k with floor(k * 1e12 / f) <= t, i.e. k * 1e12 < (t + 1) * f (t >= 0).
Edge MclkGrid::wide_last_at_or_before(sim::Time t) const {
  return static_cast<Edge>(floor_div((Wide{t} + 1) * hz_ - 1, sim::kSecond));
}

void DividerTicks::change_period(Edge now, std::int64_t period) {
  const std::int64_t next = count_through(now) + 1;
  first_ = edge_of(next);
  base_ = next - 1;
  period_ = std::max<std::int64_t>(period, 1);
}

}  // namespace sercon::chip

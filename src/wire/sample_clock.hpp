// Exact sample times for clock recovery from samples. Sample k is taken at
// start + k * num / den ps, a rational time: a 24 MHz capture has num / den = 125000 / 3.
// Every time and DPLL tick is computed from the sample index with a 128-bit intermediate,
// so nothing accumulates; only the final value is rounded (edge times to the nearest ps).
#pragma once

#include <cstdint>

#include "sercon/sim/reciprocal.hpp"

namespace sercon::wire::detail {

__extension__ typedef unsigned __int128 Wide;

inline Wide gcd_wide(Wide a, Wide b) {
  while (b != 0) {
    const Wide r = a % b;
    a = b;
    b = r;
  }
  return a;
}

// x -> floor((x * mul + add) / div) for every x < 2^64, exact. The caller makes sure that
// x * mul + add fits in 128 bits and the result in 64. When the numbers fit in 64 bits
// (every realistic capture) it is one multiplication by a reciprocal, otherwise a 128-bit
// division.
class MulDiv {
 public:
  MulDiv(Wide mul, Wide add, Wide div) {
    // floor((x m g + a) / (d g)) = floor((x m + floor(a / g)) / d): dividing out the common
    // factor of mul and div keeps the numbers small.
    const Wide g = gcd_wide(mul, div);
    mul_ = mul / g;
    add_ = add / g;
    div_ = div / g;
    fast_ = (mul_ >> 64) == 0 && (add_ >> 64) == 0 && (div_ >> 64) == 0;
    if (fast_) {
      mul64_ = static_cast<std::uint64_t>(mul_);
      add64_ = static_cast<std::uint64_t>(add_);
      reciprocal_ = sim::Reciprocal(static_cast<std::uint64_t>(div_));
    }
  }

  std::uint64_t operator()(std::uint64_t x) const {
    if (fast_) {
      std::uint64_t n = 0;
      if (!__builtin_mul_overflow(x, mul64_, &n) && !__builtin_add_overflow(n, add64_, &n))
        return reciprocal_.divide(n);
    }
    return static_cast<std::uint64_t>((Wide{x} * mul_ + add_) / div_);
  }

 private:
  Wide mul_ = 0;
  Wide add_ = 0;
  Wide div_ = 1;
  bool fast_ = false;
  std::uint64_t mul64_ = 0;
  std::uint64_t add64_ = 0;
  sim::Reciprocal reciprocal_{1};
};

// Samples at num / den ps each (num, den > 0) from start_ps, seen by a DPLL with bit period
// `period` ps. A level change between samples k-1 and k is placed at their midpoint, which
// is half-sample m = 2k - 1: start + m * num / (2 den) ps.
class SampleClock {
 public:
  SampleClock(std::uint64_t num, std::uint64_t den, std::int64_t start_ps, std::int64_t period)
      : start_(start_ps),
        // Rounded half up: for a whole-ps period (den = 1) this is start + k*T - floor(T/2).
        offset_ps_(Wide{num}, Wide{den}, 2 * Wide{den}),
        // First 16x tick at or after it: ceil(16 * m * num / (2 den period)).
        tick_(8 * Wide{num}, Wide{den} * static_cast<std::uint64_t>(period) - 1,
              Wide{den} * static_cast<std::uint64_t>(period)) {}

  // Time (ps, rounded) of half-sample m.
  std::int64_t time_ps(std::uint64_t m) const {
    return start_ + static_cast<std::int64_t>(offset_ps_(m));
  }
  // The DPLL tick of half-sample m.
  std::int64_t tick(std::uint64_t m) const { return static_cast<std::int64_t>(tick_(m)); }

 private:
  std::int64_t start_;
  MulDiv offset_ps_;
  MulDiv tick_;
};

}  // namespace sercon::wire::detail

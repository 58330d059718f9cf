// The receiver's DPLL (delta spec 2.3.1), internal to clock recovery: a counter clocked at
// 16x the bit rate, free running from the capture start. An edge is registered at the next
// tick and resets the counter; the level is sampled at count 8 (mid-bit) and then every
// 16 ticks until the next edge. So an interval of k ticks holds floor((k + 8) / 16) bits.
//
// The DPLL works on tick numbers, which the front ends compute exactly: from an edge time
// in ps (tick_of_ps), or from a sample index at a rational sample period (SampleClock), so
// a sample rate whose period is not a whole number of picoseconds keeps its timing.
#pragma once

#include <cstddef>
#include <cstdint>

#include "sercon/wire/clock_recovery.hpp"

namespace sercon::wire::detail {

class Dpll {
 public:
  Dpll(RecoveredLine& out, std::int64_t bit_period_ps, bool level)
      : out_(out), period_(bit_period_ps), level_(level) {}

  // A level change at 16x tick `tick` (the first tick at or after it), which happened at
  // t ps (rounded to the picosecond). Non-decreasing ticks, tick >= 0.
  void edge(std::int64_t tick, std::int64_t t) {
    std::size_t bits = 0;
    if (!locked_) {
      // No phase before the first edge: count back from it, bit boundaries lined up with
      // it, the bits whose mid-point lies after the capture start.
      bits = static_cast<std::size_t>((tick + 8) / 16);
      out_.anchors.push_back({0, t - static_cast<std::int64_t>(bits) * period_});
      locked_ = true;
    } else {
      bits = static_cast<std::size_t>((tick - last_tick_ + 8) / 16);
    }
    out_.bits.append_run(level_, bits);
    const std::size_t index = out_.bits.size();
    if (!out_.anchors.empty() && out_.anchors.back().bit == index)
      out_.anchors.back().time_ps = t;  // the previous interval was a glitch: re-sync here
    else
      out_.anchors.push_back({index, t});
    level_ = !level_;
    last_tick_ = tick;
  }

  // The capture ends at 16x tick `tick`: the bits whose sample point (mid-bit) lies before.
  void finish(std::int64_t tick) {
    out_.bits.append_run(level_, static_cast<std::size_t>((tick - last_tick_ + 8) / 16));
  }

 private:
  RecoveredLine& out_;
  std::int64_t period_;
  bool level_;
  bool locked_ = false;
  std::int64_t last_tick_ = 0;
};

// First 16x tick at or after t for a DPLL started at start_ps: ceil(16 (t - start) / period)
// without overflow (start <= t).
inline std::int64_t tick_of_ps(std::int64_t t, std::int64_t start_ps, std::int64_t period) {
  const std::int64_t d = t - start_ps;
  const std::int64_t q = d / period;
  const std::int64_t r = d % period;
  return 16 * q + (16 * r + period - 1) / period;
}

}  // namespace sercon::wire::detail

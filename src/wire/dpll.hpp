// The receiver's DPLL (delta spec 2.3.1), internal to clock recovery: a counter clocked at
// 16x the bit rate, free running from the capture start. An edge is registered at the next
// tick and resets the counter; the level is sampled at count 8 (mid-bit) and then every
// 16 ticks until the next edge. So an interval of k ticks holds floor((k + 8) / 16) bits.
#pragma once

#include <cstddef>
#include <cstdint>

#include "sercon/wire/clock_recovery.hpp"

namespace sercon::wire::detail {

class Dpll {
 public:
  Dpll(RecoveredLine& out, std::int64_t start_ps, std::int64_t bit_period_ps, bool level)
      : out_(out), start_(start_ps), period_(bit_period_ps), level_(level) {}

  // A level change at t (non-decreasing times, start <= t).
  void edge(std::int64_t t) {
    const std::int64_t tick = tick_of(t);
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

  // The capture ends at t: bits whose sample point (mid-bit) lies before t.
  void finish(std::int64_t t) {
    const std::int64_t tick = tick_of(t);
    out_.bits.append_run(level_, static_cast<std::size_t>((tick - last_tick_ + 8) / 16));
  }

 private:
  // First 16x tick at or after t: ceil(16 (t - start) / period) without overflow.
  std::int64_t tick_of(std::int64_t t) const {
    const std::int64_t d = t - start_;
    const std::int64_t q = d / period_;
    const std::int64_t r = d % period_;
    return 16 * q + (16 * r + period_ - 1) / period_;
  }

  RecoveredLine& out_;
  std::int64_t start_;
  std::int64_t period_;
  bool level_;
  bool locked_ = false;
  std::int64_t last_tick_ = 0;
};

}  // namespace sercon::wire::detail

// Bit-rate detection from edge intervals. The shortest common interval is one bit (a
// telegram has `00` somewhere, and fill follows a flag with `0 0`); snap it to a SERCOS
// rate (sercos-facts §1), then check that the intervals really are whole bits at that
// rate. If they are not, the capture lacks one-bit intervals: try the next faster rate.
#include <algorithm>
#include <cmath>
#include <iterator>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "sercon/wire/clock_recovery.hpp"

namespace sercon::wire {
namespace {

constexpr std::size_t kMinIntervals = 8;
constexpr double kSnapTolerance = 0.05;  // what the DPLL can follow over 8-bit runs
constexpr double kMaxResidual = 0.4;     // |d/T - round(d/T)| for an interval that fits

std::string rate_text(std::int64_t period_ps) {
  return fmt::format("{:.3f} ns = {:.3f} Mbit/s", static_cast<double>(period_ps) / 1000.0,
                     1e6 / static_cast<double>(period_ps));
}

// Intervals that are not a whole number (>= 1) of bits at period t; a few glitches are
// allowed (one in a thousand).
bool fits(std::span<const std::int64_t> intervals, double t) {
  std::size_t misfits = 0;
  for (std::int64_t d : intervals) {
    const double bits = static_cast<double>(d) / t;
    const double whole = std::round(bits);
    if (whole < 1.0 || std::abs(bits - whole) > kMaxResidual) ++misfits;
  }
  return misfits * 1000 <= intervals.size();
}

}  // namespace

std::int64_t detect_bit_period(std::span<const std::int64_t> intervals_ps) {
  if (intervals_ps.size() < kMinIntervals)
    throw RecoveryError(fmt::format(
        "clock recovery: {} edge intervals are too few to detect the bit rate (need {}); "
        "give the bit period",
        intervals_ps.size(), kMinIntervals));
  std::vector<std::int64_t> sorted(intervals_ps.begin(), intervals_ps.end());
  std::sort(sorted.begin(), sorted.end());
  if (sorted.front() <= 0)
    throw RecoveryError("clock recovery: edge interval of " + std::to_string(sorted.front()) +
                        " ps; intervals must be positive");
  // Shortest common interval: from the 0.1th percentile (ignores rare glitches) up to 1.6x
  // it, which holds one-bit intervals with up to ±3/8 bit of error but no two-bit ones.
  const std::int64_t low = sorted[sorted.size() / 1000];
  const auto first = std::lower_bound(sorted.begin(), sorted.end(), low);
  const auto last = std::lower_bound(sorted.begin(), sorted.end(), low + low * 3 / 5);
  const std::int64_t base = *(first + (last - first) / 2);

  // Refine over every interval of up to 16 bits: total time / total bits.
  double time = 0;
  double bits = 0;
  for (std::int64_t d : sorted) {
    const double n = std::round(static_cast<double>(d) / static_cast<double>(base));
    if (n < 1 || n > 16) continue;
    time += static_cast<double>(d);
    bits += n;
  }
  const double measured = time / bits;  // base itself counts, so bits >= 1

  std::size_t snapped = std::size(kBitPeriodsPs);
  for (std::size_t i = 0; i < std::size(kBitPeriodsPs); ++i) {
    const auto t = static_cast<double>(kBitPeriodsPs[i]);
    if (std::abs(measured - t) <= kSnapTolerance * t) snapped = i;
  }
  if (snapped == std::size(kBitPeriodsPs))
    throw RecoveryError(fmt::format(
        "clock recovery: the edge intervals give a bit period of {}, not within {:.0f}% of a "
        "SERCOS rate (2, 4, 8, 16 Mbit/s); give the bit period",
        rate_text(static_cast<std::int64_t>(measured)), kSnapTolerance * 100));
  // Check the fit at the measured period (scaled to each faster rate), so a line a few
  // percent off nominal still fits; report the nominal period.
  for (std::size_t i = snapped + 1; i-- > 0;) {
    const double scale =
        static_cast<double>(kBitPeriodsPs[i]) / static_cast<double>(kBitPeriodsPs[snapped]);
    if (fits(intervals_ps, measured * scale)) return kBitPeriodsPs[i];
  }
  throw RecoveryError(
      fmt::format("clock recovery: edge intervals are not whole bit times at {} or any faster "
                  "SERCOS rate (noise or glitches?); give the bit period",
                  rate_text(kBitPeriodsPs[snapped])));
}

}  // namespace sercon::wire

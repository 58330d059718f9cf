// Bit-rate detection from edge intervals. The shortest common interval is one bit (a
// telegram has `00` somewhere, and fill follows a flag with `0 0`): take the nearest
// SERCOS rate (sercos-facts §1), measure the period against it, require it within 5%,
// then check that the intervals really are whole bits at that rate. If they are not, the
// capture lacks one-bit intervals: try the next faster rate.
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
constexpr double kSnapTolerance = 0.05;    // what the DPLL can follow over 8-bit runs
constexpr double kMaxResidual = 0.45;      // |d/T - round(d/T)| for an interval that fits
constexpr double kMaxMeanResidual = 0.18;  // over all intervals
constexpr double kMaxDutyOffset = 0.3;     // duty-cycle distortion taken out, bits
constexpr double kLongestLevelBits = 8;    // idle fill (sercos-facts §1)
constexpr double kDarkBits = 64;           // longer: no signal, not the line code
constexpr std::size_t kMaxLongLevelsPercent = 1;

std::string rate_text(std::int64_t period_ps) {
  return fmt::format("{:.3f} ns = {:.3f} Mbit/s", static_cast<double>(period_ps) / 1000.0,
                     1e6 / static_cast<double>(period_ps));
}

// Half the difference between the mean signed residuals of the two levels' intervals (even
// and odd positions, as the edges alternate): the duty-cycle distortion of a receiver whose
// rising edges come early and falling edges late (or the reverse) lengthens one level's
// intervals and shortens the other's by the same amount. Bounded, so it can only take out a
// distortion the DPLL follows (±1/8 bit an edge shifts an interval by ±1/4).
double duty_offset(std::span<const std::int64_t> intervals, double t) {
  double sum[2] = {0, 0};
  std::size_t count[2] = {0, 0};
  for (std::size_t i = 0; i < intervals.size(); ++i) {
    const double bits = static_cast<double>(intervals[i]) / t;
    sum[i % 2] += bits - std::round(bits);
    ++count[i % 2];
  }
  if (count[0] == 0 || count[1] == 0) return 0;
  const double offset =
      (sum[0] / static_cast<double>(count[0]) - sum[1] / static_cast<double>(count[1])) / 2;
  return std::clamp(offset, -kMaxDutyOffset, kMaxDutyOffset);
}

// Whether the intervals are whole numbers (>= 1) of bits at period t, once the duty-cycle
// distortion is taken out: at most one in a thousand may be off by more than kMaxResidual
// (glitches), and the mean residual must be small. Jitter of ±J gives a mean of about 2J/3;
// a wrong rate such as 3 Mbit/s read as 4 gives about 0.22, a faster line read at half its
// rate 0.5 on every odd interval. And the line code must hold: no level lasts 9 to 64 bits
// (sercos-facts §1: stuffing ends runs of 1s in a frame, idle fill changes level every 8
// bits), so a slower line read at a multiple of its rate, whose 8-bit fill would read as
// 16 or 32 bits, does not fit; longer levels are dark or light and not counted.
bool fits(std::span<const std::int64_t> intervals, double t) {
  const double offset = duty_offset(intervals, t);
  std::size_t misfits = 0;
  std::size_t long_levels = 0;
  double residual_sum = 0;
  for (std::size_t i = 0; i < intervals.size(); ++i) {
    const double bits = static_cast<double>(intervals[i]) / t - (i % 2 == 0 ? offset : -offset);
    const double whole = std::round(bits);
    const double residual = std::abs(bits - whole);
    residual_sum += residual;
    if (whole < 1.0 || residual > kMaxResidual) ++misfits;
    if (whole > kLongestLevelBits && whole <= kDarkBits) ++long_levels;
  }
  return misfits * 1000 <= intervals.size() &&
         long_levels * 100 <= kMaxLongLevelsPercent * intervals.size() &&
         residual_sum <= kMaxMeanResidual * static_cast<double>(intervals.size());
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
  // Shortest common interval: from the 0.1th percentile p (ignores rare glitches) up to
  // 2p, which holds one-bit intervals but never two-bit ones. Its median is near one bit
  // (biased low under heavy jitter, which the next steps absorb).
  const std::int64_t low = sorted[sorted.size() / 1000];
  const auto first = std::lower_bound(sorted.begin(), sorted.end(), low);
  const auto last = std::lower_bound(sorted.begin(), sorted.end(), 2 * low);
  const std::int64_t base = *(first + (last - first) / 2);

  // The SERCOS rate nearest to it (rates are a factor 2 apart: within a factor sqrt 2).
  std::size_t snapped = std::size(kBitPeriodsPs);
  for (std::size_t i = 0; i < std::size(kBitPeriodsPs); ++i) {
    const double ratio = static_cast<double>(base) / static_cast<double>(kBitPeriodsPs[i]);
    if (ratio >= 1 / std::sqrt(2.0) && ratio < std::sqrt(2.0)) snapped = i;
  }
  if (snapped == std::size(kBitPeriodsPs))
    throw RecoveryError(fmt::format(
        "clock recovery: the shortest common edge interval is {}, not near a SERCOS rate "
        "(2, 4, 8, 16 Mbit/s); give the bit period",
        rate_text(base)));
  // Measure the period: total time / total bits over the intervals of up to 8 bits that
  // are clearly whole bits at that rate (odd intervals of a faster line, at half-bit
  // residue, would bias it).
  double time = 0;
  double bits = 0;
  const auto nominal = static_cast<double>(kBitPeriodsPs[snapped]);
  for (std::int64_t d : sorted) {
    const double x = static_cast<double>(d) / nominal;
    const double n = std::round(x);
    if (n < 1 || n > 8 || std::abs(x - n) > 0.3) continue;
    time += static_cast<double>(d);
    bits += n;
  }
  const double measured = bits > 0 ? time / bits : static_cast<double>(base);
  if (std::abs(measured - nominal) > kSnapTolerance * nominal)
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
                  "SERCOS rate (noise, glitches, a change of rate?); give the bit period",
                  rate_text(kBitPeriodsPs[snapped])));
}

}  // namespace sercon::wire

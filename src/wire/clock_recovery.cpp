// Clock recovery front ends: validate the capture, find its edges, get the bit period
// (given or detected), and run the DPLL over the edges.
#include "sercon/wire/clock_recovery.hpp"

#include <algorithm>
#include <bit>
#include <cstdint>
#include <numeric>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "dpll.hpp"
#include "sample_clock.hpp"

namespace sercon::wire {
namespace {

constexpr std::size_t kDetectEdges = std::size_t{1} << 20;  // enough for the histogram
// From samples the line holds at most half as many bits as the caller's samples, so this
// only guards the arithmetic. An edge list can span any time with a few edges (a VCD of 100
// bytes with a 100 s timescale), so its line is held to 2^31 bits (256 MiB packed: 134 s at
// 16 Mbit/s, 18 min at 2 Mbit/s) rather than allocating gigabytes for it.
constexpr std::int64_t kMaxSampleBits = std::int64_t{1} << 34;  // 2 GiB of packed line bits
constexpr std::int64_t kMaxEdgeBits = std::int64_t{1} << 31;    // 256 MiB of packed line bits

// The capture must fit the arithmetic and the memory: a clear error instead of overflow.
void check_span(std::int64_t start_ps, std::int64_t end_ps, std::int64_t bit_period,
                std::int64_t max_bits) {
  std::int64_t span = 0;
  if (__builtin_sub_overflow(end_ps, start_ps, &span) || span / bit_period > max_bits)
    throw RecoveryError(fmt::format(
        "clock recovery: a capture from {} ps to {} ps holds more than {} bits at {} ps per "
        "bit; too long (is the time unit or the bit rate wrong?)",
        start_ps, end_ps, max_bits, bit_period));
}

constexpr std::uint64_t kPsPerSecond = 1'000'000'000'000;

// "7812 ps", "41666.667 ps": a sample period of num / den ps for messages.
std::string sample_period_text(std::uint64_t num, std::uint64_t den) {
  if (den == 1) return fmt::format("{} ps", num);
  return fmt::format("{:.3f} ps", static_cast<double>(num) / static_cast<double>(den));
}

std::int64_t checked_period(std::int64_t period) {
  if (period <= 0)
    throw RecoveryError(fmt::format("clock recovery: bit period {} ps must be positive", period));
  return period;
}

}  // namespace

std::int64_t RecoveredLine::time_of_bit(std::size_t i) const {
  const auto after = std::upper_bound(anchors.begin(), anchors.end(), i,
                                      [](std::size_t bit, const Anchor& a) { return bit < a.bit; });
  if (after == anchors.begin())  // no anchor yet (empty line): plain bit periods
    return static_cast<std::int64_t>(i) * bit_period_ps;
  const Anchor& a = *(after - 1);
  return a.time_ps + static_cast<std::int64_t>(i - a.bit) * bit_period_ps;
}

RecoveredLine recover_from_edges(bool initial_level, std::span<const Edge> edges,
                                 std::int64_t start_ps, std::int64_t end_ps,
                                 const RecoveryOptions& options) {
  if (end_ps < start_ps)
    throw RecoveryError(fmt::format("clock recovery: capture ends ({} ps) before it starts ({} ps)",
                                    end_ps, start_ps));
  // Keep the real level changes, checking order and range.
  std::vector<std::int64_t> times;
  times.reserve(edges.size());
  bool level = initial_level;
  std::int64_t previous = start_ps;
  for (std::size_t i = 0; i < edges.size(); ++i) {
    const Edge& e = edges[i];
    if (e.time_ps < start_ps || e.time_ps > end_ps)
      throw RecoveryError(
          fmt::format("clock recovery: edge {} at {} ps is outside the capture "
                      "[{}, {}] ps",
                      i, e.time_ps, start_ps, end_ps));
    if (e.time_ps < previous)
      throw RecoveryError(fmt::format(
          "clock recovery: edges out of order: edge {} at {} ps comes after one at {} ps", i,
          e.time_ps, previous));
    previous = e.time_ps;
    if (e.level == level) continue;  // not a change of level
    level = e.level;
    times.push_back(e.time_ps);
  }
  if (times.empty())
    throw RecoveryError("clock recovery: the capture has no edges, so there is no bit clock");

  RecoveredLine out;
  if (options.bit_period_ps) {
    out.bit_period_ps = checked_period(*options.bit_period_ps);
  } else {
    std::vector<std::int64_t> intervals;
    intervals.reserve(times.size());
    for (std::size_t i = 1; i < times.size(); ++i)
      if (times[i] > times[i - 1]) intervals.push_back(times[i] - times[i - 1]);
    out.bit_period_ps = detect_bit_period(intervals);
  }
  check_span(start_ps, end_ps, out.bit_period_ps, kMaxEdgeBits);
  out.bits.reserve(static_cast<std::size_t>((end_ps - start_ps) / out.bit_period_ps) + 64);
  out.anchors.reserve(times.size() + 1);
  detail::Dpll dpll(out, out.bit_period_ps, initial_level);
  for (std::int64_t t : times) dpll.edge(detail::tick_of_ps(t, start_ps, out.bit_period_ps), t);
  dpll.finish(detail::tick_of_ps(end_ps, start_ps, out.bit_period_ps));
  return out;
}

namespace {

// Calls f(k) for every sample k >= 1 whose level differs from sample k - 1, in order.
// Word-parallel: x ^ (x << 1 | carry) marks changes, countr_zero walks them.
template <typename F>
void for_each_change(std::span<const std::uint64_t> words, std::size_t sample_count, F&& f) {
  const std::size_t full = sample_count / 64;
  const unsigned tail = static_cast<unsigned>(sample_count % 64);
  std::uint64_t carry = words[0] & 1u;  // sample 0 has nothing before it: no change
  for (std::size_t j = 0; j <= full && j < words.size(); ++j) {
    std::uint64_t w = words[j];
    std::uint64_t changes = w ^ ((w << 1) | carry);
    if (j == full) {
      if (tail == 0) break;
      changes &= (std::uint64_t{1} << tail) - 1;
    }
    carry = w >> 63;
    const std::size_t base = j * 64;
    while (changes != 0) {
      if (!f(base + static_cast<std::size_t>(std::countr_zero(changes)))) return;
      changes &= changes - 1;
    }
  }
}

// The sample-based front end for a rational sample period of num / den ps (reduced).
RecoveredLine recover_samples(std::span<const std::uint64_t> words, std::size_t sample_count,
                              std::uint64_t num, std::uint64_t den, std::int64_t start_ps,
                              const RecoveryOptions& options) {
  if (sample_count == 0) throw RecoveryError("clock recovery: the capture has no samples");
  if (sample_count / 64 > words.size() ||
      (sample_count / 64 == words.size() && sample_count % 64 != 0))
    throw RecoveryError(fmt::format("clock recovery: {} samples do not fit in {} words",
                                    sample_count, words.size()));
  // The capture lasts sample_count * num / den ps; it must fit the time axis.
  const detail::Wide duration = detail::Wide{sample_count} * num / den;
  const detail::Wide room =
      static_cast<detail::Wide>(static_cast<std::uint64_t>(INT64_MAX) -
                                static_cast<std::uint64_t>(std::max<std::int64_t>(start_ps, 0)));
  if (duration > room)
    throw RecoveryError(
        fmt::format("clock recovery: {} samples of {} from {} ps run past the time range",
                    sample_count, sample_period_text(num, den), start_ps));

  RecoveredLine out;
  if (options.bit_period_ps) {
    out.bit_period_ps = checked_period(*options.bit_period_ps);
  } else {
    // Intervals for the histogram: exact for a whole-ps period, else rounded to the ps
    // (detection is a statistical estimate; the DPLL below uses exact times).
    const double ps_per_sample = static_cast<double>(num) / static_cast<double>(den);
    std::vector<std::int64_t> intervals;
    std::size_t last = 0;
    bool any = false;
    for_each_change(words, sample_count, [&](std::size_t k) {
      if (any) {
        const std::size_t n = k - last;
        intervals.push_back(
            den == 1 ? static_cast<std::int64_t>(n * num)
                     : static_cast<std::int64_t>(static_cast<double>(n) * ps_per_sample + 0.5));
      }
      last = k;
      any = true;
      return intervals.size() < kDetectEdges;
    });
    if (!any)
      throw RecoveryError(fmt::format(
          "clock recovery: the capture has no edges in {} samples, so there is no bit clock",
          sample_count));
    out.bit_period_ps = detect_bit_period(intervals);
  }
  if (detail::Wide{static_cast<std::uint64_t>(out.bit_period_ps)} * den < 2 * detail::Wide{num})
    throw RecoveryError(
        fmt::format("clock recovery: bit period {} ps is shorter than 2 sample periods ({} each); "
                    "the capture cannot resolve this rate",
                    out.bit_period_ps, sample_period_text(num, den)));

  const detail::SampleClock clock(num, den, start_ps, out.bit_period_ps);
  // The last sample covers up to the midpoint after it, half-sample 2 * sample_count - 1.
  const std::uint64_t end_half = 2 * std::uint64_t{sample_count} - 1;
  const std::int64_t end_ps = clock.time_ps(end_half);
  check_span(start_ps, end_ps, out.bit_period_ps, kMaxSampleBits);
  out.bits.reserve(static_cast<std::size_t>((end_ps - start_ps) / out.bit_period_ps) + 64);
  detail::Dpll dpll(out, out.bit_period_ps, (words[0] & 1u) != 0);
  bool any = false;
  for_each_change(words, sample_count, [&](std::size_t k) {
    const std::uint64_t m = 2 * std::uint64_t{k} - 1;
    dpll.edge(clock.tick(m), clock.time_ps(m));
    any = true;
    return true;
  });
  if (!any)
    throw RecoveryError(fmt::format(
        "clock recovery: the capture has no edges in {} samples, so there is no bit clock",
        sample_count));
  dpll.finish(clock.tick(end_half));
  return out;
}

}  // namespace

RecoveredLine recover_from_samples(std::span<const std::uint64_t> words, std::size_t sample_count,
                                   std::int64_t sample_period_ps, std::int64_t start_ps,
                                   const RecoveryOptions& options) {
  if (sample_period_ps <= 0)
    throw RecoveryError(
        fmt::format("clock recovery: sample period {} ps must be positive", sample_period_ps));
  return recover_samples(words, sample_count, static_cast<std::uint64_t>(sample_period_ps), 1,
                         start_ps, options);
}

RecoveredLine recover_from_samples(std::span<const std::uint64_t> words, std::size_t sample_count,
                                   SampleRate rate, std::int64_t start_ps,
                                   const RecoveryOptions& options) {
  if (rate.hz == 0) throw RecoveryError("clock recovery: sample rate 0 Hz must be positive");
  // 1e12 / rate ps per sample, as a reduced fraction: 24 MHz is 125000 / 3 ps.
  const std::uint64_t g = std::gcd(kPsPerSecond, rate.hz);
  return recover_samples(words, sample_count, kPsPerSecond / g, rate.hz / g, start_ps, options);
}

}  // namespace sercon::wire

// Clock recovery front ends: validate the capture, find its edges, get the bit period
// (given or detected), and run the DPLL over the edges.
#include "sercon/wire/clock_recovery.hpp"

#include <algorithm>
#include <bit>
#include <cstdint>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "dpll.hpp"

namespace sercon::wire {
namespace {

constexpr std::size_t kDetectEdges = std::size_t{1} << 20;  // enough for the histogram
constexpr std::int64_t kMaxBits = std::int64_t{1} << 34;    // 2 GiB of packed line bits

// The capture must fit the arithmetic and the memory: a clear error instead of overflow.
void check_span(std::int64_t start_ps, std::int64_t end_ps, std::int64_t bit_period) {
  std::int64_t span = 0;
  if (__builtin_sub_overflow(end_ps, start_ps, &span) || span / bit_period > kMaxBits)
    throw RecoveryError(fmt::format(
        "clock recovery: a capture from {} ps to {} ps holds more than {} bits at {} ps per "
        "bit; too long",
        start_ps, end_ps, kMaxBits, bit_period));
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
  check_span(start_ps, end_ps, out.bit_period_ps);
  out.bits.reserve(static_cast<std::size_t>((end_ps - start_ps) / out.bit_period_ps) + 64);
  out.anchors.reserve(times.size() + 1);
  detail::Dpll dpll(out, start_ps, out.bit_period_ps, initial_level);
  for (std::int64_t t : times) dpll.edge(t);
  dpll.finish(end_ps);
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

}  // namespace

RecoveredLine recover_from_samples(std::span<const std::uint64_t> words, std::size_t sample_count,
                                   std::int64_t sample_period_ps, std::int64_t start_ps,
                                   const RecoveryOptions& options) {
  if (sample_period_ps <= 0)
    throw RecoveryError(
        fmt::format("clock recovery: sample period {} ps must be positive", sample_period_ps));
  if (sample_count == 0) throw RecoveryError("clock recovery: the capture has no samples");
  if (sample_count / 64 > words.size() ||
      (sample_count / 64 == words.size() && sample_count % 64 != 0))
    throw RecoveryError(fmt::format("clock recovery: {} samples do not fit in {} words",
                                    sample_count, words.size()));
  std::int64_t duration = 0;
  std::int64_t end_ps = 0;
  if (sample_count > static_cast<std::size_t>(INT64_MAX) ||
      __builtin_mul_overflow(static_cast<std::int64_t>(sample_count), sample_period_ps,
                             &duration) ||
      __builtin_add_overflow(start_ps, duration, &end_ps))
    throw RecoveryError(
        fmt::format("clock recovery: {} samples of {} ps from {} ps run past the time range",
                    sample_count, sample_period_ps, start_ps));
  const std::int64_t half = sample_period_ps / 2;
  // A change between samples k-1 and k happened somewhere in between: take the middle.
  const auto time_of = [&](std::size_t k) {
    return start_ps + static_cast<std::int64_t>(k) * sample_period_ps - half;
  };

  RecoveredLine out;
  if (options.bit_period_ps) {
    out.bit_period_ps = checked_period(*options.bit_period_ps);
  } else {
    std::vector<std::int64_t> intervals;
    std::size_t last = 0;
    bool any = false;
    for_each_change(words, sample_count, [&](std::size_t k) {
      if (any) intervals.push_back(static_cast<std::int64_t>(k - last) * sample_period_ps);
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
  if (out.bit_period_ps < 2 * sample_period_ps)
    throw RecoveryError(fmt::format(
        "clock recovery: bit period {} ps is shorter than 2 sample periods ({} ps each); "
        "the capture cannot resolve this rate",
        out.bit_period_ps, sample_period_ps));

  end_ps -= half;  // time_of(sample_count): the last sample covers up to here
  check_span(start_ps, end_ps, out.bit_period_ps);
  out.bits.reserve(static_cast<std::size_t>((end_ps - start_ps) / out.bit_period_ps) + 64);
  detail::Dpll dpll(out, start_ps, out.bit_period_ps, (words[0] & 1u) != 0);
  bool any = false;
  for_each_change(words, sample_count, [&](std::size_t k) {
    dpll.edge(time_of(k));
    any = true;
    return true;
  });
  if (!any)
    throw RecoveryError(fmt::format(
        "clock recovery: the capture has no edges in {} samples, so there is no bit clock",
        sample_count));
  dpll.finish(end_ps);
  return out;
}

}  // namespace sercon::wire

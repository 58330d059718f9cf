// Line bits from oversampled logic captures, recovered the way the SERCON816's DPLL does
// it (delta spec 2.3.1): a state machine clocked at 16x the bit rate that re-syncs its
// phase on every edge and samples the level in the middle of each bit. Rates are those
// of sercos-facts §1: 2, 4, 8, 16 Mbit/s (bit = 500, 250, 125, 62.5 ns).
//
// Tolerance (docs/wire.md): recovery is exact for edge jitter up to ±7/32 bit from edge
// times and ±5/32 bit from samples (so the required ±1/8 always). Beyond that an interval
// may gain or lose a bit; the decoder then reports the frame as an error and resyncs.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <stdexcept>
#include <vector>

#include "sercon/wire/line_bits.hpp"

namespace sercon::wire {

// Bad input to clock recovery; the message names the problem.
class RecoveryError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct Edge {
  std::int64_t time_ps = 0;
  bool level = false;  // level after the edge
};

struct RecoveryOptions {
  // The bit period if known (e.g. 62'500 for 16 Mbit/s). Unset: detect it from the
  // edge-interval histogram and snap to the SERCOS rate within 5%, else throw.
  std::optional<std::int64_t> bit_period_ps;
};

struct RecoveredLine {
  LineBits bits;
  std::int64_t bit_period_ps = 0;
  // Re-sync points: line bit `bit` starts at time_ps (an edge, exactly). Sorted by bit.
  struct Anchor {
    std::size_t bit = 0;
    std::int64_t time_ps = 0;
  };
  std::vector<Anchor> anchors;

  // Start of bit i in ps (i may be bits.size()): the last anchor at or before i plus whole
  // bit periods, so it is exact at edges and follows the jitter of the capture.
  std::int64_t time_of_bit(std::size_t i) const;
};

// Nominal bit periods in ps of the four SERCOS rates, fastest first (62.5 ns is 62'500).
inline constexpr std::int64_t kBitPeriodsPs[4] = {62'500, 125'000, 250'000, 500'000};

// From an edge list: the level before the first edge, then edges (time order, inside
// [start_ps, end_ps]); an edge that does not change the level is ignored.
RecoveredLine recover_from_edges(bool initial_level, std::span<const Edge> edges,
                                 std::int64_t start_ps, std::int64_t end_ps,
                                 const RecoveryOptions& options = {});

// A sample rate in Hz. Its own type, so that it cannot be mistaken for a period in ps.
struct SampleRate {
  std::uint64_t hz = 0;
};

// From samples: sample k is bit k%64 of words[k/64] (1 = high), taken at
// start_ps + k * sample_period_ps.
RecoveredLine recover_from_samples(std::span<const std::uint64_t> words, std::size_t sample_count,
                                   std::int64_t sample_period_ps, std::int64_t start_ps = 0,
                                   const RecoveryOptions& options = {});

// From samples taken at `rate`: sample k at start_ps + k * 1e12 / rate.hz ps, exactly. The
// time of every sample is computed from k in rational arithmetic (no accumulated rounding),
// so rates whose period is not a whole number of picoseconds (24 MHz: 41 666.67 ps; 12, 48,
// 6 MHz) keep their timing over any capture length; edge and bit times are rounded to the
// picosecond one by one. Same results as the period overload when 1e12 / rate.hz is whole.
RecoveredLine recover_from_samples(std::span<const std::uint64_t> words, std::size_t sample_count,
                                   SampleRate rate, std::int64_t start_ps = 0,
                                   const RecoveryOptions& options = {});

// The detection alone: the bit period (ps) of a standard rate that explains the edge
// intervals (ps, each > 0, in the order of the edges: the two levels alternate, which the
// duty-cycle correction relies on). Throws RecoveryError if none does.
std::int64_t detect_bit_period(std::span<const std::int64_t> intervals_ps);

}  // namespace sercon::wire

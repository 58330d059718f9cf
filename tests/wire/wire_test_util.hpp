// Shared helpers for the wire tests: seeded random telegrams, NRZI-decoded views of a
// line, and jittered edges/samples made from line bits.
#pragma once

#include <algorithm>
#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "sercon/wire/clock_recovery.hpp"
#include "sercon/wire/line_bits.hpp"
#include "sercon/wire/telegram.hpp"

namespace sercon::wire::test {

inline Telegram random_telegram(std::mt19937_64& rng, std::size_t min_size, std::size_t max_size) {
  std::uniform_int_distribution<std::size_t> size(min_size, max_size);
  std::uniform_int_distribution<unsigned> byte(0, 255);
  Telegram t;
  t.address = static_cast<std::uint8_t>(byte(rng));
  t.data.resize(size(rng));
  for (auto& b : t.data) b = static_cast<std::uint8_t>(byte(rng));
  return t;
}

// Line levels as '0'/'1'.
inline std::string levels_string(const LineBits& bits) {
  std::string s;
  for (std::size_t i = 0; i < bits.size(); ++i) s += bits[i] ? '1' : '0';
  return s;
}

// NRZI-decoded bits ('1' = no level change) given the level before bit 0.
inline std::string decoded_string(const LineBits& bits, bool level_before) {
  std::string s;
  bool prev = level_before;
  for (std::size_t i = 0; i < bits.size(); ++i) {
    s += bits[i] == prev ? '1' : '0';
    prev = bits[i];
  }
  return s;
}

// Edges of `bits` at bit period `period` from time 0, each moved by shift(level after it)
// ps. The capture spans [0, bits.size() * period].
template <class Shift>
std::vector<Edge> shifted_edges(const LineBits& bits, std::int64_t period, Shift shift) {
  std::vector<Edge> edges;
  for (std::size_t i = 1; i < bits.size(); ++i)
    if (bits[i] != bits[i - 1])
      edges.push_back({static_cast<std::int64_t>(i) * period + shift(bits[i]), bits[i]});
  return edges;
}

// Each edge moved by uniform random jitter in [-jitter, +jitter] ps.
inline std::vector<Edge> jittered_edges(const LineBits& bits, std::int64_t period,
                                        std::int64_t jitter, std::mt19937_64& rng) {
  std::uniform_int_distribution<std::int64_t> shift(-jitter, jitter);
  return shifted_edges(bits, period, [&](bool) { return shift(rng); });
}

// Edges of `bits` at bit period `period` from time 0 with duty-cycle distortion: every
// rising edge `shift` ps early and every falling edge `shift` ps late (or the reverse for a
// negative shift), so high levels last 2 * shift longer and low levels as much shorter.
inline std::vector<Edge> distorted_edges(const LineBits& bits, std::int64_t period,
                                         std::int64_t shift) {
  return shifted_edges(bits, period, [shift](bool rising) { return rising ? -shift : shift; });
}

// Edges of `bits` each moved by exactly +jitter or -jitter ps at random (the worst case of
// a jitter bound: intervals off by 0 or 2 * jitter).
inline std::vector<Edge> bimodal_edges(const LineBits& bits, std::int64_t period,
                                       std::int64_t jitter, std::mt19937_64& rng) {
  std::bernoulli_distribution late(0.5);
  return shifted_edges(bits, period, [&](bool) { return late(rng) ? jitter : -jitter; });
}

// Samples of a line given by its edges: sample k (at k * sample_period) is the level
// after the last edge at or before that time. Packed LSB first in 64-bit words.
inline std::vector<std::uint64_t> sample_edges(bool initial_level, const std::vector<Edge>& edges,
                                               std::size_t sample_count,
                                               std::int64_t sample_period) {
  std::vector<std::uint64_t> words((sample_count + 63) / 64, 0);
  bool level = initial_level;
  std::size_t next = 0;
  for (std::size_t k = 0; k < sample_count; ++k) {
    const std::int64_t t = static_cast<std::int64_t>(k) * sample_period;
    while (next < edges.size() && edges[next].time_ps <= t) level = edges[next++].level;
    if (level) words[k / 64] |= std::uint64_t{1} << (k % 64);
  }
  return words;
}

// Samples of a line given by its edges at an exact sample rate, computed here separately
// from the library's arithmetic: sample k is taken at k * 1e12 / rate_hz ps and is the
// level after the last edge at or before that time. So an edge at e ps shows from sample
// ceil(e * rate_hz / 1e12) on (128-bit integers). The capture ends at end_ps: samples
// 0 .. ceil(end_ps * rate_hz / 1e12) - 1.
struct SampledLine {
  std::vector<std::uint64_t> words;  // sample k is bit k % 64 of words[k / 64]
  std::size_t count = 0;
};

inline SampledLine sample_edges_at_rate(bool initial_level, const std::vector<Edge>& edges,
                                        std::int64_t end_ps, std::uint64_t rate_hz) {
  __extension__ typedef unsigned __int128 Wide;
  const auto first_sample_at = [&](std::int64_t t) {
    const Wide n = Wide{static_cast<std::uint64_t>(t)} * rate_hz;
    const Wide ps_per_second = 1'000'000'000'000;
    return static_cast<std::size_t>((n + ps_per_second - 1) / ps_per_second);
  };
  SampledLine s;
  s.count = first_sample_at(end_ps);
  s.words.assign((s.count + 63) / 64, 0);
  const auto set_high = [&](std::size_t from, std::size_t to) {  // samples [from, to)
    to = std::min(to, s.count);
    while (from < to) {
      const std::size_t stop = std::min(to, (from / 64 + 1) * 64);
      const std::size_t n = stop - from;
      const std::uint64_t ones = n == 64 ? ~std::uint64_t{0} : (std::uint64_t{1} << n) - 1;
      s.words[from / 64] |= ones << (from % 64);
      from = stop;
    }
  };
  bool level = initial_level;
  std::size_t from = 0;  // first sample of the current level
  for (const Edge& e : edges) {
    const std::size_t at = first_sample_at(e.time_ps);
    if (level) set_high(from, at);
    level = e.level;
    from = at;
  }
  if (level) set_high(from, s.count);
  return s;
}

// `bits` (line bit i from i * period to (i + 1) * period ps) sampled at rate_hz.
inline SampledLine sample_line_at_rate(const LineBits& bits, std::int64_t period,
                                       std::uint64_t rate_hz) {
  std::vector<Edge> edges;
  for (std::size_t i = 1; i < bits.size(); ++i)
    if (bits[i] != bits[i - 1]) edges.push_back({static_cast<std::int64_t>(i) * period, bits[i]});
  return sample_edges_at_rate(bits[0], edges, static_cast<std::int64_t>(bits.size()) * period,
                              rate_hz);
}

}  // namespace sercon::wire::test

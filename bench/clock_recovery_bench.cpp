// Clock recovery throughput in samples per second (target: >= 250 M samples/s, one core):
// an 8 Mbit/s line with ±1/8-bit edge jitter sampled 8x at 64 MHz (15 625 ps, the period
// overload), and 6x at 48 MHz (20 833.33 ps, not a whole number of ps: the rate overload
// with its exact rational sample times).
#include <benchmark/benchmark.h>

#include <cstdint>
#include <random>
#include <stdexcept>

#include "sercon/wire/clock_recovery.hpp"
#include "sercon/wire/encoder.hpp"
#include "wire_bench_stream.hpp"

namespace {

using namespace sercon::wire;

constexpr std::int64_t kBit = 125'000;  // 8 Mbit/s
constexpr std::uint64_t kPsPerSecond = 1'000'000'000'000;

struct Capture {
  LineBits line;
  std::vector<std::uint64_t> words;
  std::size_t samples = 0;
};

// The benchmark stream on the line, edges with ±1/8-bit random jitter, sampled at rate_hz:
// sample k at k * 1e12 / rate_hz ps is the level after the last edge at or before it.
Capture make_capture(std::uint64_t rate_hz) {
  __extension__ typedef unsigned __int128 Wide;
  Capture cap;
  LineEncoder enc(true);
  enc.idle(16);
  for (const auto& it : bench::make_stream(500)) {
    enc.telegram(it.telegram);
    enc.idle(it.idle_after);
  }
  cap.line = enc.take();
  const auto line_ps = static_cast<std::uint64_t>(cap.line.size()) * kBit;
  cap.samples = static_cast<std::size_t>(Wide{line_ps} * rate_hz / kPsPerSecond);
  cap.words.assign((cap.samples + 63) / 64, 0);
  std::mt19937_64 rng(1);
  std::uniform_int_distribution<std::int64_t> jitter(-kBit / 8, kBit / 8);
  bool level = cap.line[0];
  std::int64_t next_edge = -1;  // time of the next edge, -1 = none pending
  std::size_t bit = 1;
  for (std::size_t k = 0; k < cap.samples; ++k) {
    // floor of the exact sample time: an edge at a whole ps is at or before it alike.
    const auto t = static_cast<std::int64_t>(Wide{k} * kPsPerSecond / rate_hz);
    while (next_edge < 0 && bit < cap.line.size()) {
      if (cap.line[bit] != cap.line[bit - 1])
        next_edge = static_cast<std::int64_t>(bit) * kBit + jitter(rng);
      ++bit;
    }
    if (next_edge >= 0 && next_edge <= t) {
      level = !level;
      next_edge = -1;
    }
    if (level) cap.words[k / 64] |= std::uint64_t{1} << (k % 64);
  }
  return cap;
}

template <typename Recover>
void run(benchmark::State& state, const Capture& c, Recover&& recover) {
  for (auto _ : state) {
    RecoveredLine r = recover(c);
    if (!(r.bits == c.line)) {
      state.SkipWithError("recovered line differs");
      break;
    }
    benchmark::DoNotOptimize(r);
  }
  const auto total = static_cast<std::int64_t>(c.samples) * state.iterations();
  state.SetItemsProcessed(total);
  state.counters["samples/s"] =
      benchmark::Counter(static_cast<double>(total), benchmark::Counter::kIsRate);
}

// 64 MHz, 8x: the period overload, 15 625 ps.
const Capture& capture_64mhz() {
  static const Capture c = make_capture(64'000'000);
  return c;
}

// 48 MHz, 6x: the rate overload, 20 833.33 ps.
const Capture& capture_48mhz() {
  static const Capture c = make_capture(48'000'000);
  return c;
}

void BM_RecoverKnownRate(benchmark::State& state) {
  run(state, capture_64mhz(),
      [](const Capture& c) { return recover_from_samples(c.words, c.samples, 15'625, 0, {kBit}); });
}
BENCHMARK(BM_RecoverKnownRate)->Unit(benchmark::kMillisecond);

void BM_RecoverDetectRate(benchmark::State& state) {
  run(state, capture_64mhz(),
      [](const Capture& c) { return recover_from_samples(c.words, c.samples, 15'625); });
}
BENCHMARK(BM_RecoverDetectRate)->Unit(benchmark::kMillisecond);

void BM_RecoverKnownRate48MHz(benchmark::State& state) {
  run(state, capture_48mhz(), [](const Capture& c) {
    return recover_from_samples(c.words, c.samples, SampleRate{48'000'000}, 0, {kBit});
  });
}
BENCHMARK(BM_RecoverKnownRate48MHz)->Unit(benchmark::kMillisecond);

void BM_RecoverDetectRate48MHz(benchmark::State& state) {
  run(state, capture_48mhz(), [](const Capture& c) {
    return recover_from_samples(c.words, c.samples, SampleRate{48'000'000});
  });
}
BENCHMARK(BM_RecoverDetectRate48MHz)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();

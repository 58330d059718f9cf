// Clock recovery throughput in samples per second from an 8x oversampled capture
// (target: >= 250 M samples/s, one core).
#include <benchmark/benchmark.h>

#include <random>
#include <stdexcept>

#include "sercon/wire/clock_recovery.hpp"
#include "sercon/wire/encoder.hpp"
#include "wire_bench_stream.hpp"

namespace {

using namespace sercon::wire;

constexpr std::int64_t kBit = 125'000;      // 8 Mbit/s
constexpr std::int64_t kSample = kBit / 8;  // 8x oversampling: 64 MS/s

struct Capture {
  LineBits line;
  std::vector<std::uint64_t> words;
  std::size_t samples = 0;
};

// The benchmark stream on the line, edges with ±1/8-bit random jitter, sampled at 8x.
const Capture& capture() {
  static const Capture c = [] {
    Capture cap;
    LineEncoder enc(true);
    enc.idle(16);
    for (const auto& it : bench::make_stream(500)) {
      enc.telegram(it.telegram);
      enc.idle(it.idle_after);
    }
    cap.line = enc.take();
    cap.samples = cap.line.size() * 8;
    cap.words.assign((cap.samples + 63) / 64, 0);
    std::mt19937_64 rng(1);
    std::uniform_int_distribution<std::int64_t> jitter(-kBit / 8, kBit / 8);
    bool level = cap.line[0];
    std::int64_t next_edge = -1;  // time of the next edge, -1 = none pending
    std::size_t bit = 1;
    for (std::size_t k = 0; k < cap.samples; ++k) {
      const std::int64_t t = static_cast<std::int64_t>(k) * kSample;
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
  }();
  return c;
}

void run(benchmark::State& state, const RecoveryOptions& options) {
  const Capture& c = capture();
  for (auto _ : state) {
    RecoveredLine r = recover_from_samples(c.words, c.samples, kSample, 0, options);
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

void BM_RecoverKnownRate(benchmark::State& state) { run(state, {kBit}); }
BENCHMARK(BM_RecoverKnownRate)->Unit(benchmark::kMillisecond);

void BM_RecoverDetectRate(benchmark::State& state) { run(state, {}); }
BENCHMARK(BM_RecoverDetectRate)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();

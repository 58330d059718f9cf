// Line codec throughput in line bits per second (target: >= 1 Gbit/s each way, one core).
#include <benchmark/benchmark.h>

#include "sercon/wire/decoder.hpp"
#include "sercon/wire/encoder.hpp"
#include "wire_bench_stream.hpp"

namespace {

using namespace sercon::wire;

LineBits encode(const std::vector<bench::StreamItem>& items) {
  LineEncoder enc(true);
  enc.idle(16);
  for (const auto& it : items) {
    enc.telegram(it.telegram);
    enc.idle(it.idle_after);
  }
  return enc.take();
}

void set_rate(benchmark::State& state, std::size_t bits) {
  const auto total = static_cast<std::int64_t>(bits) * state.iterations();
  state.SetItemsProcessed(total);
  state.counters["line_bits/s"] =
      benchmark::Counter(static_cast<double>(total), benchmark::Counter::kIsRate);
}

void BM_Encode(benchmark::State& state) {
  const auto items = bench::make_stream(2000);
  std::size_t bits = 0;
  for (auto _ : state) {
    LineBits line = encode(items);
    bits = line.size();
    benchmark::DoNotOptimize(line);
  }
  set_rate(state, bits);
}
BENCHMARK(BM_Encode)->Unit(benchmark::kMillisecond);

void BM_Decode(benchmark::State& state) {
  const LineBits line = encode(bench::make_stream(2000));
  std::size_t frames = 0;
  for (auto _ : state) {
    LineDecoder dec([&frames](const DecodedFrame& f) { frames += f.ok() ? 1u : 1000000u; });
    dec.feed(line);
    dec.finish();
  }
  if (frames != static_cast<std::size_t>(state.iterations()) * std::size_t{2000 * 6})
    state.SkipWithError("decode lost or broke frames");
  set_rate(state, line.size());
}
BENCHMARK(BM_Decode)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();

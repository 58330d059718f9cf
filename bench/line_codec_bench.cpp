// Line codec throughput in line bits per second (target: >= 1 Gbit/s each way, one core),
// and the cost of one telegram the way the chip model codes it (a fresh encoder per
// telegram, a fresh decoder per burst), where per-call overhead matters more than rate.
#include <benchmark/benchmark.h>

#include <vector>

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

// Telegrams of the ring benchmark (state.range(0) data bytes: 2 for an MST, 6 for a
// 3-word AT, 48 for an 8-drive MDT), random data, 16 of them in turn.
std::vector<Telegram> ring_telegrams(std::size_t data_bytes) {
  const auto items = bench::make_stream(16);
  std::vector<Telegram> out;
  for (const auto& it : items) {
    Telegram t{it.telegram.address, it.telegram.data};
    t.data.resize(data_bytes);
    for (std::size_t i = 0; i < data_bytes; ++i)
      t.data[i] = static_cast<std::uint8_t>(it.telegram.data[i % it.telegram.data.size()] + i);
    out.push_back(std::move(t));
  }
  return out;
}

// As the chip's transmitter: one encoder per telegram, its bits taken.
void BM_EncodeTelegram(benchmark::State& state) {
  const auto telegrams = ring_telegrams(static_cast<std::size_t>(state.range(0)));
  std::size_t i = 0;
  for (auto _ : state) {
    const Telegram& t = telegrams[i++ % telegrams.size()];
    LineEncoder enc((i & 1) != 0);
    enc.telegram(t);
    LineBits bits = enc.take();
    benchmark::DoNotOptimize(bits);
  }
}
BENCHMARK(BM_EncodeTelegram)->Arg(2)->Arg(6)->Arg(48);

// As the chip's receiver (line_decode_memo.cpp): a one-bit lead-in of the other level, the
// burst from its packed bytes, finish(); each frame copied out.
void BM_DecodeTelegram(benchmark::State& state) {
  std::vector<LineBits> bursts;
  for (const Telegram& t : ring_telegrams(static_cast<std::size_t>(state.range(0)))) {
    LineEncoder enc(true);
    enc.telegram(t);
    bursts.push_back(enc.take());
  }
  std::size_t i = 0;
  for (auto _ : state) {
    const LineBits& bits = bursts[i++ % bursts.size()];
    std::vector<DecodedFrame> frames;
    LineDecoder decoder([&frames](const DecodedFrame& f) { frames.push_back(f); });
    LineBits lead_in;
    lead_in.push_back(!bits.level(0));
    decoder.feed(lead_in);
    decoder.feed(bits.packed(), bits.size());
    decoder.finish();
    if (frames.size() != 1 || !frames[0].ok()) state.SkipWithError("decode broke the frame");
    benchmark::DoNotOptimize(frames);
  }
}
BENCHMARK(BM_DecodeTelegram)->Arg(2)->Arg(6)->Arg(48);

}  // namespace

BENCHMARK_MAIN();

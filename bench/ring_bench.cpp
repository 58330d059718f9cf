// A SERCOS ring in CP4 at 16 Mbit/s, simulated as fast as it goes: master + N slaves
// (ring::Ring: fibres, repeaters), every telegram encoded to line bits and decoded by the
// receivers, lists set up through registers and DPRAM only (telegram_bench.hpp's host
// helpers). Reports `realtime_factor` (simulated seconds per CPU second) and µs of CPU per
// communication cycle. docs/performance.md, "Ring".
//
// The ring and its lists: tests/chip/cp4_ring.hpp.
// - BM_Ring8: 8 slaves, 250 µs cycle, everything in DPRAM.
// - BM_Ring254: 254 slaves, the cycle computed to fit them (see cycle_us), the master's ATs
//   2..254 and its MDT through DMA containers.
#include <benchmark/benchmark.h>

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "cp4_ring.hpp"

namespace {

using namespace sercon;
using namespace sercon::chip::telegram_testing;

void run_ring(benchmark::State& state, const Layout& layout, std::size_t cycles_per_iteration) {
  Cp4Ring bench(layout);
  bench.run_cycles(8);  // phase-up into CP4, lists settled
  if (const std::string e = bench.headers_clean(); !e.empty()) {
    state.SkipWithError(("warm-up: " + e).c_str());
    return;
  }
  std::uint16_t value = 0x1234;
  std::size_t cycles = 0;
  for (auto _ : state) {
    bench.change_data(++value);
    bench.run_cycles(cycles_per_iteration);
    cycles += cycles_per_iteration;
    if (const std::string e = bench.data_arrived(value); !e.empty()) {
      state.SkipWithError(e.c_str());
      return;
    }
  }
  if (const std::string e = bench.headers_clean(); !e.empty()) {
    state.SkipWithError(e.c_str());
    return;
  }
  const double sim_seconds =
      static_cast<double>(cycles) * static_cast<double>(bench.cycle_ps()) * 1e-12;
  state.counters["realtime_factor"] = benchmark::Counter(sim_seconds, benchmark::Counter::kIsRate);
  state.counters["us_per_cycle"] =
      benchmark::Counter(static_cast<double>(cycles) * 1e-6,
                         benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  state.counters["cycle_us"] = static_cast<double>(layout.tscyc);
}

void BM_Ring8(benchmark::State& state) { run_ring(state, layout_for(8, 250), 40); }
BENCHMARK(BM_Ring8)->Unit(benchmark::kMillisecond);

void BM_Ring254(benchmark::State& state) { run_ring(state, layout_for(254, 0), 4); }
BENCHMARK(BM_Ring254)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();

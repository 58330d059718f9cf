// The 8-slave CP4 ring of ring_bench, run for a fixed number of cycles: a deterministic
// workload for instruction counts under callgrind, where Google Benchmark's iteration count
// (chosen from wall time) would weigh the set-up differently from run to run.
//   valgrind --tool=callgrind ring_fixed_run [cycles] [slaves]
// With a slave count other than 8 (1..254), the cycle is computed to fit them, as BM_Ring254's.
// Instructions per steady cycle: the program totals of a 440- and a 40-cycle run,
// differenced, / 400 (set-up and phase-up drop out).
// docs/performance.md, "Ring".
#include <charconv>
#include <cstdio>
#include <string>
#include <string_view>

#include "cp4_ring.hpp"

int main(int argc, char** argv) {
  using namespace sercon::chip::telegram_testing;
  int cycles = 400;
  if (argc > 1) {
    const std::string_view arg = argv[1];
    const auto [end, error] = std::from_chars(arg.data(), arg.data() + arg.size(), cycles);
    if (error != std::errc{} || end != arg.data() + arg.size() || cycles < 40 || cycles % 40 != 0) {
      std::fprintf(stderr,
                   "ring_fixed_run: cycles must be a multiple of 40, at least 40 (got '%s')\n",
                   argv[1]);
      return 2;
    }
  }
  int slaves = 8;
  if (argc > 2) {
    const std::string_view arg = argv[2];
    const auto [end, error] = std::from_chars(arg.data(), arg.data() + arg.size(), slaves);
    if (error != std::errc{} || end != arg.data() + arg.size() || slaves < 1 || slaves > 254) {
      std::fprintf(stderr, "ring_fixed_run: slaves must be 1..254 (got '%s')\n", argv[2]);
      return 2;
    }
  }
  if (argc > 3) {
    std::fprintf(stderr, "ring_fixed_run: usage: ring_fixed_run [cycles] [slaves]\n");
    return 2;
  }
  Cp4Ring ring(layout_for(static_cast<std::size_t>(slaves), slaves == 8 ? 250 : 0));
  ring.run_cycles(8);  // phase-up into CP4, as ring_bench does
  std::uint16_t value = 0x1234;
  for (int i = 0; i < cycles / 40; ++i) {
    ring.change_data(++value);
    ring.run_cycles(40);
    if (const std::string e = ring.data_arrived(value); !e.empty()) {
      std::fprintf(stderr, "ring_fixed_run: %s\n", e.c_str());
      return 1;
    }
  }
  std::printf("%d cycles (+8 set-up) of master + %d slaves, CP4\n", cycles, slaves);
  return 0;
}

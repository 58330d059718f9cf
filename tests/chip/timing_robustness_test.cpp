// Brief, bad input: whatever the registers hold and whatever CYC_CLK and the MST entry
// point do, the timing units stay defined: no exception, no sanitizer report, time
// advances, and the event queue stays small (no event storm at one instant).
#include <gtest/gtest.h>

#include <random>

#include "timing_bench.hpp"

namespace sercon::chip {
namespace {

using namespace testing;

constexpr std::uint16_t kTimingRegisters[] = {
    kSerMode,   kTpCtrl,  kPhase,   kClockDiv, kTscyc0,  kTscyc1,  kTcntst,
    kTcycstart, kJtscyc1, kJtscyc2, kTconclk,  kWconclk, kConCtrl, kTdivclk,
    kDtdivclk,  kDivCtrl, kWdCtrl,  kWdTrig,   kTwdog,   kIen0A,   kIen1A};

// Small values (zero, one, a few) are where the corner cases live; some are anything.
std::uint16_t random_value(std::mt19937& rng) {
  switch (rng() % 4) {
    case 0:
      return static_cast<std::uint16_t>(rng() % 3);
    case 1:
      return static_cast<std::uint16_t>(rng() % 300);
    case 2:
      return static_cast<std::uint16_t>(0xFFFF - rng() % 3);
    default:
      return static_cast<std::uint16_t>(rng());
  }
}

TEST(TimingRobustness, RandomTrafficStaysDefined) {
  for (std::uint32_t seed = 1; seed <= 24; ++seed) {
    TimingBench b(seed % 3 == 0 ? config_410b() : ChipConfig{});
    std::mt19937 rng(seed);
    Time t = 0;
    bool cyc_clk = false;
    for (int step = 0; step < 300; ++step) {
      t += static_cast<Time>(rng() % (30 * kMicrosecond));
      b.run_to(t);
      switch (rng() % 5) {
        case 0:
        case 1: {
          const std::uint16_t reg = kTimingRegisters[rng() % std::size(kTimingRegisters)];
          std::uint16_t value = random_value(rng);
          if (reg == kSerMode && rng() % 8 != 0) value &= static_cast<std::uint16_t>(~0x0002);
          b.chip.reg_write(reg, value);
          break;
        }
        case 2:
          cyc_clk = !cyc_clk;
          b.chip.drive(Pin::CYC_CLK, sim::level_of(cyc_clk));
          break;
        case 3:
          b.cycles().mst_detected(t + static_cast<Time>(rng() % kMicrosecond));
          break;
        default:
          b.chip.reg_write(kIntStat, 0xFFFF);
          break;
      }
      ASSERT_EQ(b.now(), t) << "seed " << seed;
      ASSERT_LT(b.bench.scheduler.pending_count(), 600u) << "seed " << seed;
    }
  }
}

}  // namespace
}  // namespace sercon::chip

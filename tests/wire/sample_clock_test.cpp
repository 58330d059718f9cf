// The exact arithmetic behind sample-based clock recovery (src/wire/sample_clock.hpp):
// floor((x * mul + add) / div) is exact also where the intermediate passes 64 bits (brief: sample k
// is at k * 1e12 / rate ps, computed without accumulated error).
#include "sample_clock.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <random>
#include <vector>

namespace sercon::wire::detail {
namespace {

constexpr std::uint64_t kMax = ~std::uint64_t{0};

// floor((x * mul + add) / div) equals the plain 128-bit formula, on the fast path and
// where x * mul passes 2^64 (the 128-bit fallback), with and without a common factor.
TEST(SampleClock, MulDivIsExactAcrossTheSixtyFourBitBoundary) {
  std::mt19937_64 rng(2);
  struct Case {
    Wide mul, add, div;
  };
  const std::vector<Case> cases = {
      {125'000, 3, 6},                                    // 24 MHz: offsets of half-samples
      {8 * Wide{125'000}, 3 * 250'000 - 1, 3 * 250'000},  // 24 MHz ticks at 4 Mbit/s
      {1'000'000'000'000, 999'999'937, 2 * Wide{999'999'937}},
      {8 * Wide{1'000'000'000'000}, Wide{999'999'937} * 62'500 - 1, Wide{999'999'937} * 62'500},
      {Wide{kMax} * 4, 7, Wide{kMax} * 3},  // everything beyond 64 bits
  };
  for (const Case& c : cases) {
    const MulDiv f(c.mul, c.add, c.div);
    for (std::uint64_t x :
         {std::uint64_t{0}, std::uint64_t{1}, std::uint64_t{9'223'372}, std::uint64_t{1} << 40}) {
      const Wide expected = (Wide{x} * c.mul + c.add) / c.div;
      ASSERT_EQ(Wide{f(x)}, expected) << "x " << x;
    }
    for (int i = 0; i < 5000; ++i) {
      const std::uint64_t x = rng() >> (20 + rng() % 44);
      const Wide expected = (Wide{x} * c.mul + c.add) / c.div;
      ASSERT_EQ(Wide{f(x)}, expected) << "x " << x;
    }
  }
}

// SampleClock at 24 MHz, 4 Mbit/s: half-sample m lies at m * 125000 / 6 ps, rounded half
// up, and its tick is ceil(16 * t / 250000) of the exact t, also 100 M samples in.
TEST(SampleClock, TwentyFourMegahertzTimesAndTicks) {
  const SampleClock clock(125'000, 3, 1'000, 250'000);
  for (std::uint64_t m : {std::uint64_t{1}, std::uint64_t{3}, std::uint64_t{5}, std::uint64_t{7},
                          std::uint64_t{199'999'999}, std::uint64_t{200'000'001}}) {
    const Wide twice_offset = Wide{m} * 125'000 * 2 / 6;  // 2 t, floored
    const auto expected_t = static_cast<std::int64_t>((twice_offset + 1) / 2) + 1'000;
    EXPECT_EQ(clock.time_ps(m), expected_t) << m;
    const Wide n = Wide{m} * 125'000 * 16;  // 16 t * 6, over 6 * 250000
    EXPECT_EQ(Wide{static_cast<std::uint64_t>(clock.tick(m))},
              (n + 6 * 250'000 - 1) / (6 * 250'000))
        << m;
  }
}

}  // namespace
}  // namespace sercon::wire::detail

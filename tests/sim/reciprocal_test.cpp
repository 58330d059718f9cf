// Division by a precomputed reciprocal (sercon/sim/reciprocal.hpp) equals division: the
// MCLK grid, the repeater's SCLK grid and the sample times of a capture rest on it
// (docs/timing.md "MCLK and the dividers", docs/serial-and-ring.md "Repeater", docs/wire.md).
#include "sercon/sim/reciprocal.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <random>
#include <vector>

namespace sercon::sim {
namespace {

constexpr std::uint64_t kMax = ~std::uint64_t{0};

std::vector<std::uint64_t> interesting_values(std::mt19937_64& rng) {
  std::vector<std::uint64_t> v = {
      1, 2, 3, 5, 6, 7, 10, 125'000, 15'625, 62'500, 1'000'000'000'000, kMax, kMax - 1};
  for (int b = 1; b < 64; ++b) {
    const std::uint64_t p = std::uint64_t{1} << b;
    v.insert(v.end(), {p - 1, p, p + 1});
  }
  for (int i = 0; i < 200; ++i) v.push_back((rng() >> (rng() % 64)) | 1);
  return v;
}

// Granlund-Montgomery division: every divisor class (1, powers of 2, 2^k +- 1, odd, the
// largest, the SCLK and bit periods of the rates) against the CPU's division, over
// numerators from 0 to 2^64 - 1.
TEST(Reciprocal, DivisionEqualsDivision) {
  std::mt19937_64 rng(1);
  const std::vector<std::uint64_t> values = interesting_values(rng);
  for (std::uint64_t d : values) {
    const Reciprocal r(d);
    ASSERT_EQ(r.divisor(), d);
    ASSERT_EQ(r.divide(0), 0u);
    for (std::uint64_t n : values) {
      ASSERT_EQ(r.divide(n), n / d) << n << " / " << d;
      for (std::uint64_t near : {n / d * d, n / d * d - 1, n / d * d + d - 1})
        ASSERT_EQ(r.divide(near), near / d) << near << " / " << d;
    }
    for (int i = 0; i < 2000; ++i) {
      const std::uint64_t n = rng();
      ASSERT_EQ(r.divide(n), n / d) << n << " / " << d;
    }
  }
}

}  // namespace
}  // namespace sercon::sim

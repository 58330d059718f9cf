// Seeded bit errors on a fibre (brief: "flip line levels in a copy of the bits; same seed →
// same errors"), caught by the FCS (facts §1: CRC-16/X.25) at the receiver.
#include "sercon/ring/bit_errors.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

#include "ring_bench.hpp"
#include "sercon/ring/fibre.hpp"

namespace sercon::ring {
namespace {

using chip::LineBurst;
using sim::Time;
using testing::Ear;
using testing::telegram_bits;

const std::vector<std::uint8_t> kData(40, 0x5A);

std::vector<chip::SharedBits> run(double p, std::uint64_t seed, int n, const chip::SharedBits& in) {
  BitErrors e;
  e.configure(p, seed);
  std::vector<chip::SharedBits> out;
  for (int i = 0; i < n; ++i) out.push_back(e.apply(in));
  return out;
}

// Brief / docs "Fibre": "same seed → same errors"; another seed, other errors.
TEST(BitErrors, SameSeedSameErrorsOtherSeedOtherErrors) {
  const auto bits = telegram_bits(7, kData);
  const auto a = run(1e-3, 42, 500, bits);
  const auto b = run(1e-3, 42, 500, bits);
  const auto c = run(1e-3, 43, 500, bits);
  bool any_hit = false, differs = false;
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(*a[i], *b[i]) << i;
    EXPECT_EQ(a[i] == bits, b[i] == bits) << i;
    any_hit = any_hit || a[i] != bits;
    differs = differs || !(*a[i] == *c[i]);
  }
  EXPECT_TRUE(any_hit);
  EXPECT_TRUE(differs);
}

// A burst without a hit is passed on as the same object (no copy); p = 0 never hits; p = 1
// flips every level.
TEST(BitErrors, NoHitNoCopyAndTheExtremes) {
  const auto bits = telegram_bits(7, kData);
  for (const auto& out : run(0.0, 1, 10, bits)) EXPECT_EQ(out, bits);
  const auto all = run(1.0, 1, 1, bits)[0];
  ASSERT_EQ(all->size(), bits->size());
  for (std::size_t i = 0; i < bits->size(); ++i) EXPECT_NE(all->level(i), bits->level(i));
  BitErrors e;
  EXPECT_THROW(e.configure(-0.1, 1), std::invalid_argument);
  EXPECT_THROW(e.configure(1.5, 1), std::invalid_argument);
  EXPECT_THROW(e.configure(std::numeric_limits<double>::quiet_NaN(), 1), std::invalid_argument);
}

// The hit rate matches p (law of large numbers; the seed makes the count exact and stable).
TEST(BitErrors, HitRateMatchesTheProbability) {
  const auto bits = telegram_bits(7, kData);
  BitErrors e;
  e.configure(1e-3, 2024);
  const int bursts = 5000;
  for (int i = 0; i < bursts; ++i) e.apply(bits);
  const double expected = 1e-3 * static_cast<double>(bits->size()) * bursts;
  EXPECT_NEAR(static_cast<double>(e.flipped()), expected, 5 * std::sqrt(expected));
}

// Through a fibre into a chip: every telegram the fibre left alone decodes, none that it
// changed does (BadFcs, Abort, a misaligned or vanished frame); the same seed, the same.
TEST(BitErrors, ErrorsOnAFibreAreCaughtByTheReceiverAndRepeatable) {
  std::vector<std::vector<bool>> outcomes;
  for (int pass = 0; pass < 2; ++pass) {
    sim::Scheduler s;
    chip::Chip rx(s, chip::ChipConfig{});
    Ear ear(rx);
    auto& unit = *rx.unit<chip::SerialUnit>();
    const Time t = unit.bit_period();
    Fibre f(s, 3.0);
    f.connect(unit.rxd());
    f.set_bit_error_rate(2e-3, 99);
    const auto bits = telegram_bits(0x21, kData);
    std::vector<bool> ok;
    int hits = 0;
    for (int i = 0; i < 300; ++i) {
      const Time at = static_cast<Time>(i) * 2000 * t;
      s.run_until(at);
      const std::uint64_t errors_before = f.bit_errors();
      const std::size_t heard_before = ear.heard.size();
      f.input().line_burst(LineBurst{at, t, bits});
      s.run_until(at + 1999 * t);
      const bool changed = f.bit_errors() != errors_before;
      hits += changed ? 1 : 0;
      std::size_t good = 0;
      for (std::size_t k = heard_before; k < ear.heard.size(); ++k)
        good += ear.heard[k].frame.ok() ? 1u : 0u;
      if (changed) {
        EXPECT_EQ(good, 0u) << i;
      } else {
        EXPECT_EQ(ear.heard.size() - heard_before, 1u) << i;
        EXPECT_EQ(good, 1u) << i;
      }
      ok.push_back(good == 1);
    }
    EXPECT_GT(hits, 50);
    outcomes.push_back(ok);
  }
  EXPECT_EQ(outcomes[0], outcomes[1]);
}

}  // namespace
}  // namespace sercon::ring

// MCLK frequencies whose period is not a whole number of picoseconds (12, 24 MHz): edge k
// is at floor(k * 1e12 / f_MCLK) ps, so nothing drifts (docs/timing.md, "MCLK and the dividers").
// Expectations are computed here from that rule alone.
#include <gtest/gtest.h>

#include <limits>
#include <vector>

#include "sercon/chip/mclk_divider.hpp"
#include "timing_bench.hpp"

namespace sercon::chip {
namespace {

using namespace testing;

// Edge k of an f-Hz MCLK (k * 1e12 fits 64 bits for the times used here).
Time edge(std::int64_t k, std::int64_t hz) { return k * sim::kSecond / hz; }
std::int64_t first_edge_at_or_after(Time t, std::int64_t hz) {
  std::int64_t k = 0;
  while (edge(k, hz) < t) ++k;
  return k;
}

ChipConfig at_hz(std::int64_t hz) {
  ChipConfig c;
  c.mclk_hz = hz;
  return c;
}

TEST(MclkGrid, EdgesAreTheFloorOfTheExactTimes) {
  for (const std::int64_t hz : {12'000'000, 24'000'000, 33'000'000, 32'000'000}) {
    const MclkGrid grid(hz);
    for (std::int64_t k : {0, 1, 2, 3, 11, 12, 1000, 123457}) {
      EXPECT_EQ(grid.time_of(k), edge(k, hz)) << hz << " " << k;
      EXPECT_EQ(grid.first_at_or_after(edge(k, hz)), k) << hz << " " << k;
      EXPECT_EQ(grid.first_at_or_after(edge(k, hz) + 1), k + 1) << hz << " " << k;
      EXPECT_EQ(grid.last_at_or_before(edge(k, hz)), k) << hz << " " << k;
      EXPECT_EQ(grid.last_at_or_before(edge(k, hz) - 1), k - 1) << hz << " " << k;
    }
  }
  // No drift after 100 simulated days (k * 1e12 is beyond 64 bits there).
  const MclkGrid grid(12'000'000);
  const std::int64_t days = 100 * 86'400;
  EXPECT_EQ(grid.time_of(12'000'000 * days), days * sim::kSecond);
  EXPECT_EQ(grid.time_of(12'000'000 * days + 1), days * sim::kSecond + 83'333);
  EXPECT_EQ(grid.first_at_or_after(days * sim::kSecond), 12'000'000 * days);
  EXPECT_EQ(grid.last_at_or_before(days * sim::kSecond - 1), 12'000'000 * days - 1);
  EXPECT_EQ(MclkGrid(12'000'000).period(), 83'334);
  EXPECT_EQ(MclkGrid::of_period(31'250).hz(), 32'000'000);
  EXPECT_THROW(MclkGrid::of_period(83'333), std::invalid_argument);
  EXPECT_THROW(MclkGrid(0), std::invalid_argument);
}

TEST(MclkGrid, ChipNextEdgeFollowsTheGrid) {
  TimingBench b(at_hz(12'000'000));
  EXPECT_EQ(b.chip.next_mclk_edge(0), 0);
  EXPECT_EQ(b.chip.next_mclk_edge(1), 83'333);
  EXPECT_EQ(b.chip.next_mclk_edge(83'334), 166'666);
  EXPECT_EQ(b.chip.next_mclk_edge(166'667), 250'000);
}

// Delta spec 2.6.3: T_WDOG = (MCLKDIV + 1) * TWDOG / f_MCLK, counted from the MCLK edge that
// registers WDOG_START. 12 MHz with MCLKDIV = 11 is a 1 µs tick; 24 MHz with MCLKDIV = 7 a
// tick of 333 333.3 ps.
TEST(MclkGrid, WatchdogExpiryAtInexactClocks) {
  struct Case {
    std::int64_t hz;
    std::uint16_t mclkdiv;
    std::uint16_t twdog;
    Time written;
  };
  for (const Case c :
       {Case{12'000'000, 11, 100, 5 * kMicrosecond + 1}, Case{12'000'000, 11, 7, 123'457},
        Case{24'000'000, 7, 7, 19'999}, Case{24'000'000, 23, 1000, 3 * kMicrosecond + 7}}) {
    TimingBench b(at_hz(c.hz));
    b.chip.reg_write(kClockDiv, c.mclkdiv);
    b.chip.reg_write(kTwdog, c.twdog);
    b.write_at(c.written, kWdCtrl, kWdogStart);
    const std::int64_t start = first_edge_at_or_after(c.written, c.hz);
    const Time expiry = edge(start + (c.mclkdiv + 1) * std::int64_t{c.twdog}, c.hz);
    if (c.mclkdiv == 11) {
      EXPECT_EQ(expiry - edge(start, c.hz), c.twdog * kMicrosecond);
    }
    EXPECT_EQ(b.read_at(expiry - 1, kWdCtrl) & (kIntWdog | kWdogStart), kWdogStart) << c.hz;
    EXPECT_EQ(b.read_at(expiry, kWdCtrl) & (kIntWdog | kWdogStart), kIntWdog) << c.hz;
  }
}

// DIV_CLK as a master at 12 and 24 MHz with a 1 µs tick and MCLKST = 5: a cycle of 250 µs
// starts at edge k * 250 * MHz; the pulse for cycle time c rises at edge
// start + 5 + (c - 3) * MHz (TCNTST = 3) and falls one tick later.
TEST(MclkGrid, DivClkPulseEdgesAtInexactClocks) {
  for (const std::int64_t mhz : {12, 24}) {
    const std::int64_t hz = mhz * 1'000'000;
    TimingBench b(at_hz(hz));
    PinLog log(b.bench.scheduler, b.pin(Pin::DIV_CLK));
    b.chip.reg_write(kClockDiv, static_cast<std::uint16_t>(5 << 8 | (mhz - 1)));
    b.chip.reg_write(kTcntst, 3);
    b.chip.reg_write(kTscyc0, 250);
    b.chip.reg_write(kTdivclk, 20);
    b.chip.reg_write(kDtdivclk, 50);
    b.chip.reg_write(kDivCtrl, 2);
    b.chip.reg_write(kSerMode, kRegmode);
    b.run_to(3 * 250 * kMicrosecond - 1);
    std::vector<PinLog::Change> expected;
    for (std::int64_t k = 0; k < 3; ++k) {
      for (std::int64_t c : {20, 70}) {
        const std::int64_t rise = k * 250 * mhz + 5 + (c - 3) * mhz;
        expected.push_back({edge(rise, hz), Level::High});
        expected.push_back({edge(rise + mhz, hz), Level::Low});
      }
    }
    EXPECT_EQ(log.changes, expected) << mhz;
  }
}

// Delta spec 2.8: BUSYN low from the colliding access to the next MCLK edge, so never
// longer than one MCLK period, also when edges are 83 333 or 83 334 ps apart.
TEST(MclkGrid, BusynUntilTheNextEdgeAt12MHz) {
  constexpr std::int64_t hz = 12'000'000;
  for (const Time at : {Time{100'000}, edge(1, hz), edge(2, hz) - 1, edge(7, hz)}) {
    TimingBench b(at_hz(hz));
    PinLog log(b.bench.scheduler, b.pin(Pin::BUSYN));
    b.run_to(at);
    b.chip.tp_ram_write(0x0123, 0x4444);
    EXPECT_EQ(b.chip.ram_read(0x0123), 0x4444);
    b.run_to(at + 10 * kMicrosecond);
    const Time end = edge(first_edge_at_or_after(at + 1, hz), hz);
    const std::vector<PinLog::Change> expected{{at, Level::Low}, {end, Level::High}};
    EXPECT_EQ(log.changes, expected) << at;
    EXPECT_LE(end - at, b.chip.mclk_period()) << at;
  }
}

// mclk_divider.hpp: edge k is at floor(k * 1e12 / f_MCLK) for every frequency, computed
// without 128-bit division where 64 bits provably suffice. These are the 128-bit formulas
// that rule was first written with; the grid must agree with them bit for bit, on both
// sides of every edge, up to times near 2^62 ps (53 days) and beyond.
__extension__ typedef __int128 Wide;
Wide floor_div(Wide n, Wide d) {
  const Wide q = n / d;
  return (n % d != 0 && n < 0) ? q - 1 : q;
}
Time ref_time_of(std::int64_t hz, std::int64_t k) {
  return static_cast<Time>(floor_div(Wide{k} * sim::kSecond, hz));
}
std::int64_t ref_first_at_or_after(std::int64_t hz, Time t) {
  if (t <= 0) return 0;
  return static_cast<std::int64_t>(floor_div(Wide{t} * hz + sim::kSecond - 1, sim::kSecond));
}
std::int64_t ref_last_at_or_before(std::int64_t hz, Time t) {
  if (t < 0) return -1;
  return static_cast<std::int64_t>(floor_div((Wide{t} + 1) * hz - 1, sim::kSecond));
}

TEST(MclkGrid, FastPathMatchesThe128BitFormula) {
  // Exact periods (1e12 % f == 0), inexact ones in the chip's 12..64 MHz, odd ones whose
  // reduced fraction is large (19 MHz + 1 and up take the 128-bit path), and the limits;
  // 244.140625 MHz: a period of 4096 ps, a power of two, where the reciprocal the exact
  // path divides by is furthest from 2^64 / period.
  const std::vector<std::int64_t> clocks{
      16'000'000, 20'000'000,      25'000'000,   32'000'000, 40'000'000, 50'000'000,
      64'000'000, 12'000'000,      24'000'000,   33'000'000, 12'345'678, 48'000'000,
      63'999'999, 12'000'001,      18'000'001,   19'000'001, 64'000'001, 1,
      7,          999'999'999'989, sim::kSecond, 244'140'625};
  constexpr std::int64_t kMax = std::numeric_limits<std::int64_t>::max();
  std::uint64_t seed = 0x9E37'79B9'7F4A'7C15u;
  const auto random_below = [&seed](std::int64_t bound) {  // splitmix64, reproducible
    seed += 0x9E37'79B9'7F4A'7C15u;
    std::uint64_t z = seed;
    z = (z ^ (z >> 30)) * 0xBF58'476D'1CE4'E5B9u;
    z = (z ^ (z >> 27)) * 0x94D0'49BB'1331'11EBu;
    return static_cast<std::int64_t>((z ^ (z >> 31)) % static_cast<std::uint64_t>(bound));
  };
  for (const std::int64_t hz : clocks) {
    const MclkGrid grid(hz);
    std::vector<Time> times{0,
                            1,
                            2,
                            -1,
                            -2,
                            std::numeric_limits<std::int64_t>::min(),
                            kMax,
                            kMax - 1,
                            std::int64_t{1} << 62,
                            (std::int64_t{1} << 62) - 1};
    for (int i = 0; i < 2000; ++i) {
      // Every magnitude from 1 ps to 2^63.
      times.push_back(random_below(std::int64_t{1} << (i % 63 + 1)));
      times.push_back((std::int64_t{1} << 62) + random_below(sim::kSecond));
      times.push_back(kMax - random_below(sim::kSecond));
    }
    std::vector<std::int64_t> edges{0, 1, -1, kMax, std::numeric_limits<std::int64_t>::min()};
    for (const Time t : times) {
      const std::int64_t k = ref_last_at_or_before(hz, t);
      edges.insert(edges.end(), {k, t});     // t: also edges far beyond 64 bits
      if (k < kMax) edges.push_back(k + 1);  // no signed overflow (UBSan)
      if (k > std::numeric_limits<std::int64_t>::min()) edges.push_back(k - 1);
    }
    for (const Time t : times) {
      ASSERT_EQ(grid.first_at_or_after(t), ref_first_at_or_after(hz, t)) << hz << " " << t;
      ASSERT_EQ(grid.last_at_or_before(t), ref_last_at_or_before(hz, t)) << hz << " " << t;
    }
    for (const std::int64_t k : edges) {
      ASSERT_EQ(grid.time_of(k), ref_time_of(hz, k)) << hz << " " << k;
      const Time at = ref_time_of(hz, k);
      // Only edges whose time (and the next one's) fits 64 bits.
      if (k < 0 || floor_div((Wide{k} + 1) * sim::kSecond, hz) >= kMax) continue;
      // Both sides of the edge.
      ASSERT_EQ(grid.last_at_or_before(at), k) << hz << " " << k;
      ASSERT_EQ(grid.first_at_or_after(at), k) << hz << " " << k;
      ASSERT_EQ(grid.first_at_or_after(at + 1), k + 1) << hz << " " << k;
      if (at > 0) {
        ASSERT_EQ(grid.last_at_or_before(at - 1), k - 1) << hz << " " << k;
      }
    }
  }
}

// nth_edge_after's fast path (an exact grid, a time not too late, a few edges) gives what
// the general formula gives: the n-th edge after the first at or after t; so does
// nth_edge_at, with the edge's index.
TEST(MclkGrid, NthEdgeAfterMatchesTheGeneralFormula) {
  const std::vector<std::int64_t> clocks{16'000'000, 32'000'000,   64'000'000, 33'000'000,
                                         1,          sim::kSecond, 244'140'625};
  constexpr std::int64_t kMax = std::numeric_limits<std::int64_t>::max();
  constexpr std::int64_t kMin = std::numeric_limits<std::int64_t>::min();
  const std::vector<std::int64_t> counts{
      0, 1, 3, 4, MclkGrid::kFewEdges - 1, MclkGrid::kFewEdges, MclkGrid::kFewEdges + 1, -1};
  for (const std::int64_t hz : clocks) {
    const MclkGrid grid(hz);
    std::vector<Time> times{0, 1, 2, -1, kMax, kMax - 1, std::int64_t{1} << 62, kMin, kMin + 1};
    const auto around = [&times](Time at) {  // the edge at `at` and both sides of it
      times.insert(times.end(), {at - 1, at});
      if (at < kMax) times.push_back(at + 1);
    };
    for (std::int64_t k : {std::int64_t{1}, std::int64_t{1000}, kMax / sim::kSecond}) {
      around(grid.time_of(k));
    }
    // Around the end of the fast path, for every grid: the last edges that fit 64 bits.
    const std::int64_t last = grid.last_at_or_before(kMax);
    for (std::int64_t i = MclkGrid::kFewEdges + 3; i >= 0; --i) around(grid.time_of(last - i));
    for (const Time t : times) {
      const std::int64_t first = grid.first_at_or_after(t);
      for (const std::int64_t n : counts) {
        if (n > 0 && first > last - n) continue;  // the n-th edge does not fit 64 bits
        ASSERT_EQ(grid.nth_edge_after(t, n), grid.time_of(first + n)) << hz << " " << t << " " << n;
        const MclkGrid::EdgeAt at = grid.nth_edge_at(t, n);
        ASSERT_EQ(at.edge, first + n) << hz << " " << t << " " << n;
        ASSERT_EQ(at.time, grid.time_of(first + n)) << hz << " " << t << " " << n;
      }
    }
  }
}

}  // namespace
}  // namespace sercon::chip

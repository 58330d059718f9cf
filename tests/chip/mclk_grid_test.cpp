// MCLK frequencies whose period is not a whole number of picoseconds (12, 24 MHz): edge k
// is at floor(k * 1e12 / f_MCLK) ps, so nothing drifts (docs/timing.md, "MCLK grid").
// Expectations are computed here from that rule alone.
#include <gtest/gtest.h>

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

}  // namespace
}  // namespace sercon::chip

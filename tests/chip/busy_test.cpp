// BUSYN: "becomes active if an access to an address of the dual port RAM is performed
// simultaneously to an access to the same memory location by the internal telegram
// processing" (datasheet Table 1); "has to have a maximum length of one cycle of MCLK"
// (delta spec 2.8). Times are exact picoseconds on the MCLK grid from time 0.
#include <gtest/gtest.h>

#include <array>
#include <utility>
#include <vector>

#include "chip_fixture.hpp"

namespace sercon::chip {
namespace {

using sim::Level;
using sim::Time;
using testing::ChipOnBench;

// Records every BUSYN edge with its time.
struct EdgeLog {
  EdgeLog(ChipOnBench& bench, Pin p) {
    bench.chip->pin(p).watch(
        [this, &bench](Level l) { edges.emplace_back(bench.scheduler.now(), l); });
  }
  std::vector<std::pair<Time, Level>> edges;
};

ChipConfig mclk(std::int64_t hz) {
  ChipConfig c;
  c.mclk_hz = hz;
  return c;
}

TEST(Busy, SameWordInTheSameMclkPeriodPullsBusynLowUntilTheNextEdge) {
  ChipOnBench bench(mclk(32'000'000));  // T = 31 250 ps
  EdgeLog log(bench, Pin::BUSYN);
  bench.scheduler.run_until(100'000);  // period 3 runs 93 750 .. 125 000
  bench.chip->tp_ram_write(0x0123, 0x4444);
  bench.scheduler.run_until(110'000);
  EXPECT_EQ(bench.chip->ram_read(0x0123), 0x4444);  // the µP sees the new value
  EXPECT_EQ(bench.chip->pin(Pin::BUSYN).level(), Level::Low);
  bench.scheduler.run_until(200'000);
  ASSERT_EQ(log.edges.size(), 2u);
  EXPECT_EQ(log.edges[0], std::make_pair(Time{110'000}, Level::Low));
  EXPECT_EQ(log.edges[1], std::make_pair(Time{125'000}, Level::High));
  EXPECT_LE(log.edges[1].first - log.edges[0].first, bench.chip->mclk_period());
}

TEST(Busy, AnAccessAtThePeriodStartLastsExactlyOneMclk) {
  ChipOnBench bench(mclk(64'000'000));  // T = 15 625 ps
  EdgeLog log(bench, Pin::BUSYN);
  bench.scheduler.run_until(15'625 * 4);
  bench.chip->tp_ram_read(7);
  bench.chip->ram_write(7, 1);
  bench.scheduler.run_until(15'625 * 10);
  ASSERT_EQ(log.edges.size(), 2u);
  EXPECT_EQ(log.edges[0].first, 15'625 * 4);
  EXPECT_EQ(log.edges[1].first, 15'625 * 5);
}

TEST(Busy, OtherWordOrOtherPeriodDoesNotCollide) {
  ChipOnBench bench(mclk(32'000'000));
  EdgeLog log(bench, Pin::BUSYN);
  bench.chip->tp_ram_read(10);
  bench.chip->ram_read(11);           // another word
  bench.scheduler.run_until(31'250);  // next period
  bench.chip->ram_read(10);
  bench.scheduler.run_until(1'000'000);
  EXPECT_TRUE(log.edges.empty());
}

// The bus cycle reports the collision; a µP that touches the word first is not delayed.
TEST(Busy, BusResultReportsTheCollision) {
  ChipOnBench bench;
  BusCycle c;
  c.mcsn0 = false;
  c.mcsn1 = false;
  c.bhen = false;
  c.address = 0x0040;
  EXPECT_FALSE(bench.chip->bus(c).busy);
  bench.chip->tp_ram_write(0x0020, 0xFFFF);
  EXPECT_TRUE(bench.chip->bus(c).busy);
  EXPECT_TRUE(bench.chip->bus(c).busy);  // again in the same period: still busy
  c.address = 0x0042;
  EXPECT_FALSE(bench.chip->bus(c).busy);
}

// Several collisions in one period give one low pulse; a collision in the next period
// (after the rise) gives a second one.
TEST(Busy, RepeatedCollisionsStayWithinOnePeriodEach) {
  ChipOnBench bench(mclk(50'000'000));  // T = 20 000 ps
  EdgeLog log(bench, Pin::BUSYN);
  bench.scheduler.run_until(5'000);
  bench.chip->tp_ram_write(1, 1);
  bench.chip->ram_read(1);
  bench.scheduler.run_until(9'000);
  bench.chip->ram_read(1);
  bench.scheduler.run_until(20'000);
  bench.chip->tp_ram_write(1, 2);
  bench.chip->ram_read(1);
  bench.scheduler.run_until(100'000);
  const std::vector<std::pair<Time, Level>> expected = {
      {5'000, Level::Low}, {20'000, Level::High}, {20'000, Level::Low}, {40'000, Level::High}};
  EXPECT_EQ(log.edges, expected);
}

// A reset ends a busy pulse at once (BUSYN inactive after reset).
TEST(Busy, ResetReleasesBusyn) {
  ChipOnBench bench;
  bench.chip->tp_ram_read(3);
  bench.chip->ram_read(3);
  EXPECT_EQ(bench.chip->pin(Pin::BUSYN).level(), Level::Low);
  bench.chip->reg_write(0x01, 0x0002);
  EXPECT_EQ(bench.chip->pin(Pin::BUSYN).level(), Level::High);
  bench.scheduler.run_until(1'000'000);
  EXPECT_EQ(bench.chip->pin(Pin::BUSYN).level(), Level::High);
}

// Table 1 BUSYN: an access "performed simultaneously to an access to the same memory
// location by the internal telegram processing". Two events at the same picosecond run in
// the order they were scheduled, which the chip cannot know: a µP access whose event runs
// just before the telegram processor's at the same instant collides as the reverse order
// does (BusResultReportsTheCollision: the µP's access itself is not delayed). A telegram
// processor access later in the period does not pull BUSYN for an access already made
// (datasheet 3.5.5 / 3.5.7 t_MBSY: BUSYN falls within 15 ns of the strobe's start).
TEST(Busy, InternalAccessAtTheInstantOfAHostAccessCollidesWhicheverRunsFirst) {
  for (const int kind : {0, 1, 2}) {      // one word, a run over it, a word beside it
    ChipOnBench bench(mclk(32'000'000));  // period 3 runs 93 750 .. 125 000
    EdgeLog log(bench, Pin::BUSYN);
    Chip& chip = *bench.chip;
    bench.scheduler.at(100'000, [&chip] { chip.ram_read(0x0123); });
    bench.scheduler.at(100'000, [&chip, kind] {
      const std::array<std::uint16_t, 3> words{1, 2, 3};
      if (kind == 0) chip.tp_ram_write(0x0123, 0x4444);
      if (kind == 1) chip.tp_ram_write_run(0x0122, words);
      if (kind == 2) chip.tp_ram_write(0x0124, 0x4444);
    });
    bench.scheduler.at(110'000, [&chip] { chip.tp_ram_read(0x0123); });  // later: no effect
    bench.scheduler.run_until(200'000);
    using E = std::pair<Time, Level>;
    const std::vector<E> expected =
        kind == 2 ? std::vector<E>{}
                  : std::vector<E>{{100'000, Level::Low}, {125'000, Level::High}};
    EXPECT_EQ(log.edges, expected) << kind;
  }
}

TEST(Busy, InternalPortCountsItsAccessesNotTheHosts) {
  ChipOnBench bench;
  bench.chip->tp_ram_read(1);
  bench.chip->tp_ram_write(2, 2);
  bench.chip->ram_read(1);
  EXPECT_EQ(bench.chip->tp_ram_accesses(), 2u);
}

TEST(Busy, InternalPortChecksTheAddress) {
  ChipOnBench bench;
  EXPECT_THROW(bench.chip->tp_ram_read(2048), std::out_of_range);
  EXPECT_THROW(bench.chip->tp_ram_write(2048, 0), std::out_of_range);
}

// A run through the internal port is the same as one access per word: every word of it
// collides in the period, the words beside it do not, and each counts as an access.
TEST(Busy, RunOfWordsMarksEachWordLikeSingleAccesses) {
  ChipOnBench bench(mclk(32'000'000));
  bench.scheduler.run_until(100'000);
  const std::array<std::uint16_t, 3> words{0x1111, 0x2222, 0x3333};
  bench.chip->tp_ram_write_run(0x0100, words);
  std::array<std::uint16_t, 3> back{};
  bench.chip->tp_ram_read_run(0x0100, back);
  EXPECT_EQ(back, words);
  EXPECT_EQ(bench.chip->tp_ram_accesses(), 6u);
  BusCycle c;
  c.mcsn0 = false;
  c.mcsn1 = false;
  c.bhen = false;
  for (std::uint16_t w = 0x00FF; w <= 0x0103; ++w) {
    c.address = static_cast<std::uint16_t>(2 * w);  // byte address of the word
    EXPECT_EQ(bench.chip->bus(c).busy, w >= 0x0100 && w <= 0x0102) << w;
  }
}

TEST(Busy, RunBeyondTheRamDoesNothing) {
  ChipOnBench bench;
  std::array<std::uint16_t, 2> out{};
  EXPECT_THROW(bench.chip->tp_ram_read_run(2047, out), std::out_of_range);
  EXPECT_THROW(bench.chip->tp_ram_write_run(2047, out), std::out_of_range);
  EXPECT_EQ(bench.chip->tp_ram_accesses(), 0u);
}

}  // namespace
}  // namespace sercon::chip

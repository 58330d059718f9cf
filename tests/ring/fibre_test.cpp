// Fibre (docs/serial-and-ring.md, "Fibre"): delay = length x ps per metre (default 5 ns/m,
// project decision), delivery scheduled at the far end's time with the same bits, breaks
// (datasheet Table 1 L_ERRN: "when the receive signal is missing"; facts §5 FIBBR "fibre
// broken / ring open") and restores at any time.
#include "sercon/ring/fibre.hpp"

#include <gtest/gtest.h>

#include <limits>
#include <stdexcept>
#include <vector>

#include "ring_bench.hpp"

namespace sercon::ring {
namespace {

using chip::LineBurst;
using chip::LineCondition;
using sim::Time;
using testing::Ear;
using testing::Recorder;
using testing::telegram_bits;

const std::vector<std::uint8_t> kData = {0x10, 0x20, 0x30, 0x40};

// Decision (docs "Fibre"): delay = round(length x ps per metre), 5 ns/m by default; a
// negative or non-finite length is refused.
TEST(Fibre, DelayIsLengthTimesDelayPerMetre) {
  sim::Scheduler s;
  EXPECT_EQ(Fibre(s, 12.5).delay(), 62'500);  // 5 ns/m default
  EXPECT_EQ(Fibre(s, 0.0).delay(), 0);
  EXPECT_EQ(Fibre(s, 100.0, 4'900).delay(), 490'000);
  EXPECT_EQ(Fibre(s, 0.0001).delay(), 1);  // rounded to the picosecond
  EXPECT_THROW(Fibre(s, -1.0), std::invalid_argument);
  EXPECT_THROW(Fibre(s, std::numeric_limits<double>::infinity()), std::invalid_argument);
  EXPECT_THROW(Fibre(s, std::numeric_limits<double>::quiet_NaN()), std::invalid_argument);
  EXPECT_THROW(Fibre(s, 1.0, -5), std::invalid_argument);
}

// Line contract: the far end is told when a change happens there (now == at), bursts keep
// their shared bits (no per-hop copy).
TEST(Fibre, DeliversEachChangeAtTheFarEndWhenItHappens) {
  sim::Scheduler s;
  Fibre f(s, 20.0);  // 100 ns
  Recorder far(s);
  f.connect(far);
  const auto bits = telegram_bits(1, kData);
  f.input().line_condition(0, LineCondition::Idle, 62'500);
  f.input().line_burst(LineBurst{1'000'000, 62'500, bits});
  s.run_until(999'999);
  f.input().line_condition(2'000'000, LineCondition::Dark, 0);  // announced ahead
  s.run_until(10'000'000);
  ASSERT_EQ(far.events.size(), 4u);  // the far end's state at connect, then 3 changes
  EXPECT_EQ(far.events[0].condition, LineCondition::Dark);
  EXPECT_EQ(far.events[1].at, 100'000);
  EXPECT_EQ(far.events[1].now, 100'000);
  EXPECT_EQ(far.events[1].condition, LineCondition::Idle);
  EXPECT_TRUE(far.events[2].burst);
  EXPECT_EQ(far.events[2].at, 1'100'000);
  EXPECT_EQ(far.events[2].now, 1'100'000);
  EXPECT_EQ(far.events[2].bits.get(), bits.get());
  EXPECT_EQ(far.events[3].at, 2'100'000);
  EXPECT_EQ(far.events[3].condition, LineCondition::Dark);
}

// Line contract (line.hpp): "Calls come in time order per line"; bad input is refused.
TEST(Fibre, RefusesChangesOutOfOrderOrInThePast) {
  sim::Scheduler s;
  Fibre f(s, 1.0);
  f.input().line_condition(1000, LineCondition::Idle, 62'500);
  EXPECT_THROW(f.input().line_condition(999, LineCondition::Dark, 0), std::invalid_argument);
  EXPECT_THROW(f.input().line_burst(LineBurst{2000, 62'500, nullptr}), std::invalid_argument);
  EXPECT_THROW(f.input().line_condition(2000, LineCondition::ZeroBits, 0), std::invalid_argument);
  s.run_until(5000);
  EXPECT_THROW(f.input().line_condition(4000, LineCondition::Dark, 0), std::invalid_argument);
  EXPECT_THROW(f.break_at(4000), std::invalid_argument);
  EXPECT_THROW(f.restore_at(4000), std::invalid_argument);
}

// A break in the middle of a telegram cuts it at the break instant: the receiver decodes an
// aborted telegram ending there; with no edges FIBBR rises FIBBRTIM (255) bit times later
// and INT_FIBBR latches. Restored, the signal returns and FIBBR clears.
TEST(Fibre, BreakMidTelegramCutsItAndRaisesFibbrAndRestoreClearsIt) {
  sim::Scheduler s;
  chip::Chip rx(s, chip::ChipConfig{});
  Ear ear(rx);
  auto& unit = *rx.unit<chip::SerialUnit>();
  const Time t = unit.bit_period();
  Fibre f(s, 10.0);  // 50 ns
  f.connect(unit.rxd());
  f.input().line_condition(0, LineCondition::Idle, t);
  const auto bits = telegram_bits(0x42, kData);
  const Time start = 1000 * t;
  s.run_until(start);
  f.input().line_burst(LineBurst{start, t, bits});
  const Time cut = start + f.delay() + 30 * t + 1234;
  f.break_at(cut);
  s.run_until(cut + 254 * t);
  ASSERT_EQ(ear.heard.size(), 1u);
  EXPECT_EQ(ear.heard[0].frame.error, wire::FrameError::Abort);
  EXPECT_EQ(ear.heard[0].start, start + f.delay());
  EXPECT_EQ(ear.heard[0].end, cut);
  EXPECT_FALSE(rx.reg_read(0x02) & (1u << 13));
  s.run_until(cut + 255 * t);
  EXPECT_TRUE(rx.reg_read(0x02) & (1u << 13));  // FIBBR
  EXPECT_TRUE(rx.reg_read(0x04) & (1u << 1));   // INT_FIBBR
  // Telegrams sent while broken are lost.
  f.input().line_burst(LineBurst{s.now(), t, bits});
  s.run_until(s.now() + 1000 * t);
  EXPECT_EQ(ear.heard.size(), 1u);
  f.restore_at(s.now() + 10 * t);
  s.run_until(s.now() + 10 * t);
  EXPECT_FALSE(rx.reg_read(0x02) & (1u << 13));
  f.input().line_burst(LineBurst{s.now(), t, bits});
  s.run_until(s.now() + 1000 * t);
  ASSERT_EQ(ear.heard.size(), 2u);
  EXPECT_TRUE(ear.heard[1].frame.ok());
}

// Restored while a telegram passes: the far end gets the rest of it as idle fill (a
// fragment without its opening flag decodes to nothing).
TEST(Fibre, RestoredMidTelegramTheFarEndSeesIdle) {
  sim::Scheduler s;
  Fibre f(s, 0.0);
  Recorder far(s);
  f.connect(far);
  f.break_now();
  EXPECT_TRUE(f.broken());
  f.input().line_burst(LineBurst{0, 62'500, telegram_bits(1, kData)});
  s.run_until(10 * 62'500);
  f.restore();
  EXPECT_FALSE(f.broken());
  ASSERT_FALSE(far.events.empty());
  EXPECT_FALSE(far.events.back().burst);
  EXPECT_EQ(far.events.back().condition, LineCondition::Idle);
  EXPECT_EQ(far.events.back().period, 62'500);
  EXPECT_EQ(far.events.back().at, 10 * 62'500);
}

}  // namespace
}  // namespace sercon::ring

// The repeater (delta spec 2.3.3: "The repeater for the serial interface is switched on '1'
// and off '0' through the control bit REPON"; datasheet §1: "The slaves regenerate and
// repeat their received data or send their own telegrams"). Decisions (serial_unit_
// repeater.hpp): a delay of kRepeaterDelayBits bit times rounded up to the SCLK grid, the
// same bits object passed on, own telegram wins over a repeated one.
#include <gtest/gtest.h>

#include <vector>

#include "serial_bench.hpp"

namespace sercon::chip {
namespace {

using sim::Level;
using sim::Time;
using testing::bit_period_of;
using testing::config_at_mbit;
using testing::kRepon;
using testing::SerialBench;
using testing::telegram_bits;

constexpr Time kSclk = 15'625;  // 64 MHz

Time forwarded(Time arrival, Time bit) {
  const Time due = arrival + 2 * bit;
  return (due + kSclk - 1) / kSclk * kSclk;
}

struct Repeating : SerialBench {
  explicit Repeating(const ChipConfig& c = {}) : SerialBench(c) {
    set_sermode_bits(kRepon, true);
    light_up();
  }
};

const std::vector<std::uint8_t> kData = {0xAA, 0x55, 0x00, 0xFF};

class RepeatAt : public ::testing::TestWithParam<int> {};

// Every rate: a telegram reaching RxD at any time leaves TxD1 2 bit times later, rounded up
// to the next SCLK edge, as the very same bits object.
TEST_P(RepeatAt, TelegramsLeaveTwoBitTimesLaterOnTheSclkGrid) {
  const int mbit = GetParam();
  Repeating b(config_at_mbit(mbit));
  const Time t = bit_period_of(mbit);
  EXPECT_EQ(b.unit.bit_period(), t);
  const auto bits = telegram_bits(0x21, kData);
  for (const Time arrival : {1000 * t, 2000 * t + 1, 3000 * t + kSclk - 1}) {
    b.run_to(arrival);
    b.unit.rxd().line_burst(LineBurst{arrival, t, bits});
    b.run_to(arrival + 500 * t);
    const auto out = b.txd1.bursts();
    ASSERT_FALSE(out.empty());
    EXPECT_EQ(out.back().at, forwarded(arrival, t));
    EXPECT_EQ(out.back().now, forwarded(arrival, t));
    EXPECT_EQ(out.back().bits.get(), bits.get());  // shared, not copied
    EXPECT_EQ(out.back().period, t);
    EXPECT_EQ(b.unit.repeated_at(arrival), forwarded(arrival, t));
  }
}

INSTANTIATE_TEST_SUITE_P(serial, RepeatAt, ::testing::Values(2, 4, 8, 16),
                         [](const auto& p) { return std::to_string(p.param) + "Mbit"; });

// Conditions are repeated with the same delay: a dark input makes a dark output.
TEST(serial_Repeater, ConditionsFollowWithTheSameDelay) {
  Repeating b;
  const Time t = b.period();
  b.unit.rxd().line_condition(1000 * t, LineCondition::Idle, t);
  b.unit.rxd().line_condition(2000 * t + 5, LineCondition::Dark, 0);
  b.run_to(3000 * t);
  const auto c = b.txd1.conditions();
  ASSERT_GE(c.size(), 2u);
  EXPECT_EQ(c[c.size() - 2].condition, LineCondition::Idle);
  EXPECT_EQ(c[c.size() - 2].at, forwarded(1000 * t, t));
  EXPECT_EQ(c.back().condition, LineCondition::Dark);
  EXPECT_EQ(c.back().at, forwarded(2000 * t + 5, t));
  EXPECT_EQ(b.chip->pin(Pin::TxD1).level(), Level::Low);  // no light
}

// REPON = 0: only own telegrams leave; the line carries the own idle fill.
TEST(serial_Repeater, OffPassesNothingOn) {
  SerialBench b;  // REPON cleared by the bench
  b.light_up();
  const Time t = b.period();
  b.unit.rxd().line_burst(LineBurst{0, t, telegram_bits(1, kData)});
  b.unit.rxd().line_condition(500 * t, LineCondition::Dark, 0);
  b.run_to(1000 * t);
  EXPECT_TRUE(b.txd1.bursts().empty());
  EXPECT_EQ(b.txd1.last().condition, LineCondition::Idle);
}

// Own telegram wins (decision): a repeated telegram still going when the own one begins is
// cut there; one arriving while the own is sent is not passed on at all; afterwards the
// line again follows RxD.
TEST(serial_Repeater, OwnTelegramIsInsertedAndWins) {
  Repeating b;
  const Time t = b.period();
  const auto repeated = telegram_bits(0x31, kData);
  b.unit.rxd().line_burst(LineBurst{0, t, repeated});
  const Time out1 = forwarded(0, t);
  const Time own_start = out1 + 20 * t;
  const Time own_end = b.unit.send(own_start, 0x07, kData);
  b.run_to(own_start + 10 * t);
  b.unit.rxd().line_burst(LineBurst{own_start + 10 * t, t, repeated});  // under the own one
  b.run_to(own_end + 1000 * t);
  const auto out = b.txd1.bursts();
  ASSERT_EQ(out.size(), 2u);
  EXPECT_EQ(out[0].at, out1);
  EXPECT_EQ(out[0].bits.get(), repeated.get());
  EXPECT_EQ(out[1].at, own_start);
  EXPECT_LT(out[1].at, out[0].at + static_cast<Time>(repeated->size()) * t);  // a cut
  // After the own telegram the line follows RxD again: idle (the contract's default), and
  // a telegram after that is repeated.
  b.unit.rxd().line_burst(LineBurst{own_end + 1000 * t, t, repeated});
  b.run_to(own_end + 2000 * t);
  ASSERT_EQ(b.txd1.bursts().size(), 3u);
  EXPECT_EQ(b.txd1.bursts()[2].at, forwarded(own_end + 1000 * t, t));
}

// A telegram announced before the own one is sent, to leave after the own one ends, is not
// in its way: it leaves whole, after the own telegram (the later word, the own one, drops
// it from the line at first; what follows the own telegram brings it back).
TEST(serial_Repeater, ATelegramAnnouncedToLeaveAfterTheOwnOneLeavesWhole) {
  Repeating b;
  const Time t = b.period();
  const auto repeated = telegram_bits(0x31, kData);
  b.unit.rxd().line_condition(0, LineCondition::Idle, t);
  b.unit.rxd().line_burst(LineBurst{300 * t, t, repeated});
  const Time own_end = b.unit.send(100 * t, 0x07, kData);
  ASSERT_LT(own_end, forwarded(300 * t, t));
  b.run_to(own_end + 1000 * t);
  const auto out = b.txd1.bursts();
  ASSERT_GE(out.size(), 2u);
  EXPECT_EQ(out[out.size() - 2].at, 100 * t);
  EXPECT_EQ(out.back().at, forwarded(300 * t, t));
  EXPECT_EQ(out.back().bits.get(), repeated.get());
}

// An upstream break under the own telegram: once the own telegram is out, the line shows
// what RxD carries (dark), so the break travels on.
TEST(serial_Repeater, AfterTheOwnTelegramTheLineShowsTheReceivedCondition) {
  Repeating b;
  const Time t = b.period();
  b.unit.rxd().line_condition(0, LineCondition::Idle, t);
  const Time own_end = b.unit.send(100 * t, 0x07, kData);
  b.unit.rxd().line_condition(110 * t, LineCondition::Dark, 0);
  b.run_to(own_end + 10 * t);
  EXPECT_EQ(b.txd1.last().condition, LineCondition::Dark);
  EXPECT_EQ(b.txd1.last().at, own_end);
}

// Writing other bits of 0x01 (POLTXD here) while a telegram passes leaves it whole: only a
// change of REPON or of the bit rate changes what the line carries.
TEST(serial_Repeater, OtherModeBitsLeaveATelegramInPassageAlone) {
  Repeating b;
  const Time t = b.period();
  const auto bits = telegram_bits(0x44, kData);
  b.unit.rxd().line_burst(LineBurst{0, t, bits});
  b.run_to(forwarded(0, t) + 10 * t);
  const std::size_t told = b.txd1.events.size();
  b.set_sermode_bits(testing::kPoltxd, true);
  b.run_to(1000 * t);
  EXPECT_EQ(b.txd1.events.size(), told);
  EXPECT_TRUE(b.txd1.last().burst);
}

// REPON written while running: on takes up the received condition at once; off returns the
// line to the own idle fill.
TEST(serial_Repeater, SwitchingReponWhileRunning) {
  SerialBench b;
  b.light_up();
  const Time t = b.period();
  b.unit.rxd().line_condition(0, LineCondition::Dark, 0);
  b.run_to(10 * t);
  b.set_sermode_bits(kRepon, true);
  EXPECT_EQ(b.txd1.last().condition, LineCondition::Dark);
  EXPECT_EQ(b.txd1.last().at, 10 * t);
  b.set_sermode_bits(kRepon, false);
  EXPECT_EQ(b.txd1.last().condition, LineCondition::Idle);
}

}  // namespace
}  // namespace sercon::chip

// The transmitter: telegrams as exact bursts on the TxC grid (sercos-facts §1 frame and
// bit times), IDLE low while own data is sent (datasheet Table 1, IDLE), the idle fill's
// level carried on between telegrams, and the send() contract of serial_unit.hpp.
#include <gtest/gtest.h>

#include <stdexcept>
#include <vector>

#include "sercon/wire/fcs.hpp"
#include "serial_bench.hpp"

namespace sercon::chip {
namespace {

using sim::Level;
using sim::Time;
using testing::bit_period_of;
using testing::config_at_mbit;
using testing::PinEdges;
using testing::SerialBench;
using testing::telegram_bits;

// Line bits of a telegram counted the slow way: 2 flags + every bit of address, data and
// FCS (low byte first, LSB first) + a stuffed 0 after every five 1s in a row.
std::size_t counted_line_bits(std::uint8_t address, const std::vector<std::uint8_t>& data) {
  std::vector<std::uint8_t> bytes{address};
  bytes.insert(bytes.end(), data.begin(), data.end());
  const std::uint16_t fcs = wire::fcs16(bytes);
  bytes.push_back(static_cast<std::uint8_t>(fcs & 0xFF));
  bytes.push_back(static_cast<std::uint8_t>(fcs >> 8));
  std::size_t bits = 16;
  int ones = 0;
  for (const std::uint8_t byte : bytes) {
    for (int i = 0; i < 8; ++i) {
      ++bits;
      ones = ((byte >> i) & 1) != 0 ? ones + 1 : 0;
      if (ones == 5) {
        ++bits;
        ones = 0;
      }
    }
  }
  return bits;
}

const std::vector<std::uint8_t> kData = {0xFF, 0x00, 0x7E, 0x1F, 0xF8, 0x55, 0xFF, 0xFF};

class TransmitAtRate : public ::testing::TestWithParam<int> {};

// Facts §1: "A bit lasts 500, 250, 125, 62.5 ns"; frame = flag, address, data, FCS, flag
// with stuffing. The burst begins exactly at the requested TxC edge and ends bits x period
// later.
TEST_P(TransmitAtRate, BurstStartAndEndArePicosecondExact) {
  const int mbit = GetParam();
  SerialBench b(config_at_mbit(mbit));
  b.light_up();
  const Time t = bit_period_of(mbit);
  ASSERT_EQ(b.period(), t);
  const Time start = 100 * t;
  const std::size_t n = counted_line_bits(0x3F, kData);
  const Time end = b.unit.send(start, 0x3F, kData);
  EXPECT_EQ(end, start + static_cast<Time>(n) * t);
  EXPECT_EQ(b.unit.burst_duration(0x3F, kData), static_cast<Time>(n) * t);
  EXPECT_EQ(b.unit.transmit_free_at(), end);
  b.run_to(end + 100 * t);
  const auto bursts = b.txd1.bursts();
  ASSERT_EQ(bursts.size(), 1u);
  EXPECT_EQ(bursts[0].at, start);
  EXPECT_EQ(bursts[0].now, start);  // told when it happens, not before
  EXPECT_EQ(bursts[0].period, t);
  ASSERT_EQ(bursts[0].bits->size(), n);
  // The same bits as the wire encoder writes from the level before the opening flag.
  EXPECT_EQ(*bursts[0].bits, *telegram_bits(0x3F, kData, !bursts[0].bits->level(0)));
}

INSTANTIATE_TEST_SUITE_P(serial, TransmitAtRate, ::testing::Values(2, 4, 8, 16),
                         [](const auto& p) { return std::to_string(p.param) + "Mbit"; });

// Project decision (serial_unit.hpp, send): the transmitter is clocked by TxC, whose
// edges are at k * t_bit; a start between two edges waits for the next one.
TEST(serial_Transmitter, StartBetweenTxcEdgesWaitsForTheNextEdge) {
  SerialBench b;
  b.light_up();
  const Time t = b.period();
  const Time end = b.unit.send(10 * t + 1, 0x01, kData);
  EXPECT_EQ(b.unit.next_bit_edge(10 * t + 1), 11 * t);
  EXPECT_EQ(b.unit.next_bit_edge(11 * t), 11 * t);
  EXPECT_EQ(end, 11 * t + b.unit.burst_duration(0x01, kData));
  b.run_to(end);
  ASSERT_EQ(b.txd1.bursts().size(), 1u);
  EXPECT_EQ(b.txd1.bursts()[0].at, 11 * t);
}

// Datasheet Table 1, IDLE: "Transmitter active, active low. When transmitting own data
// IDLE is 0." Low from the opening flag's first bit to the closing flag's end; back-to-
// back telegrams keep it low without a gap.
TEST(serial_Transmitter, IdleIsLowExactlyWhileOwnDataIsSent) {
  SerialBench b;
  b.light_up();
  PinEdges idle(b, Pin::IDLE);
  const Time t = b.period();
  const Time end1 = b.unit.send(20 * t, 0x01, kData);
  const Time end2 = b.unit.send(end1, 0x02, kData);
  const Time end3 = b.unit.send(end2 + 8 * t, 0x03, kData);
  b.run_to(end3 + 10 * t);
  const std::vector<std::pair<Time, Level>> expected = {
      {20 * t, Level::Low}, {end2, Level::High}, {end2 + 8 * t, Level::Low}, {end3, Level::High}};
  EXPECT_EQ(idle.edges, expected);
  EXPECT_EQ(b.txd1.bursts().size(), 3u);
}

// serial_unit.hpp, send(): overlapping the own previous telegram, a start in the past, a
// chip in reset and stopped clocks are refused with clear exceptions.
TEST(serial_Transmitter, RefusesOverlapPastStartResetAndStoppedClocks) {
  SerialBench b;
  b.light_up();
  const Time t = b.period();
  const Time end = b.unit.send(10 * t, 0x01, kData);
  EXPECT_THROW(b.unit.send(end - t, 0x01, kData), std::logic_error);
  EXPECT_NO_THROW(b.unit.send(end, 0x01, kData));
  b.run_to(1000 * t);
  EXPECT_THROW(b.unit.send(999 * t, 0x01, kData), std::invalid_argument);
  b.chip->drive(Pin::RSTN, Level::Low);
  EXPECT_THROW(b.unit.send(2000 * t, 0x01, kData), std::logic_error);
  b.chip->drive(Pin::RSTN, Level::High);
  b.chip->drive(Pin::OUTZ, Level::High);  // Table 1: "The clocks are turned off"
  EXPECT_EQ(b.unit.bit_period(), 0);
  EXPECT_THROW(b.unit.send(2000 * t, 0x01, kData), std::logic_error);
}

// A reset drops telegrams not yet sent (and ends one being sent): IDLE goes high.
TEST(serial_Transmitter, ResetDropsPendingTelegrams) {
  SerialBench b;
  b.light_up();
  const Time t = b.period();
  b.unit.send(10 * t, 0x01, kData);
  b.unit.send(1000 * t, 0x02, kData);
  b.run_to(12 * t);
  EXPECT_EQ(b.chip->pin(Pin::IDLE).level(), Level::Low);
  b.chip->software_reset();
  EXPECT_EQ(b.chip->pin(Pin::IDLE).level(), Level::High);
  b.run_to(2000 * t);
  EXPECT_EQ(b.txd1.bursts().size(), 1u);
}

// Facts §1: idle fill "changes level once every 8 bit times"; the level is carried on from
// telegram to telegram, so the first bit of each burst (the opening flag's 0, a level
// change) follows from the last bit before it and the fill bits in between.
TEST(serial_Transmitter, LineLevelIsCarriedOnThroughTheIdleFill) {
  SerialBench b;
  b.light_up();
  const Time t = b.period();
  Time at = b.unit.send(10 * t, 0x01, kData);
  for (const Time gap : {0, 1, 7, 8, 9, 16, 17, 100}) at = b.unit.send(at + gap * t, 0x02, kData);
  b.run_to(at);
  const auto bursts = b.txd1.bursts();
  ASSERT_EQ(bursts.size(), 9u);
  const Time gaps[] = {0, 1, 7, 8, 9, 16, 17, 100};
  for (std::size_t i = 1; i < bursts.size(); ++i) {
    const wire::LineBits& before = *bursts[i - 1].bits;
    const Time fill = gaps[i - 1];
    const bool fill_changes_odd = ((fill + 7) / 8) % 2 == 1;
    const bool level_before = before.level(before.size() - 1) != fill_changes_odd;
    EXPECT_EQ(bursts[i].bits->level(0), !level_before) << "gap " << fill;
  }
}

// Facts §1 idle fill between telegrams: the line listener hears Idle at the bit rate once,
// and then only bursts (the line returns to idle at each burst's end by contract).
TEST(serial_Transmitter, TheLineIdlesBetweenTelegramsWithoutPerTelegramConditions) {
  SerialBench b;
  b.light_up();
  const Time t = b.period();
  ASSERT_FALSE(b.txd1.events.empty());
  EXPECT_EQ(b.txd1.last().condition, LineCondition::Idle);
  EXPECT_EQ(b.txd1.last().period, t);
  const std::size_t before = b.txd1.events.size();
  Time at = 10 * t;
  for (int i = 0; i < 5; ++i) at = b.unit.send(at + 50 * t, 0x01, kData);
  b.run_to(at + 100 * t);
  EXPECT_EQ(b.txd1.events.size(), before + 5);
  EXPECT_EQ(b.txd1.conditions().size(), before);
}

}  // namespace
}  // namespace sercon::chip

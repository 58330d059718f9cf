// Bit rate and SCLKO2/SCLKO4 from pins and register 0x01, checked through the chip's pins
// and bus (delta spec 2.3.1 tables, 2.3.2; facts §5 for the 410B's SWBAUD).
#include "sercon/chip/serial_clock.hpp"

#include <gtest/gtest.h>

#include <optional>
#include <string>

#include "chip_fixture.hpp"

namespace sercon::chip {
namespace {

using testing::ChipOnBench;
using testing::config_410b;

constexpr std::uint16_t kSwbaud = 1u << 6;     // 1H.6
constexpr std::uint16_t kEntsbaud = 1u << 10;  // 1H.10
constexpr std::uint16_t kSwbaud16 = 1u << 15;  // 1H.15
constexpr std::int64_t kMbit = 1'000'000;

struct Row {
  int number;
  bool entsbaud;
  std::optional<bool> sbaud;  // nullopt: "x" in the table, both levels checked
  bool sbaud16;
  std::optional<bool> swbaud;
  std::optional<bool> swbaud16;
  std::int64_t mbit;
};

// Delta spec 2.3.1, "Bit rate for SCLK = 64 MHz", rows 1..10 in table order.
constexpr Row kRows[] = {
    {1, false, true, true, std::nullopt, std::nullopt, 2},     // 0 1 1 X X -> 2
    {2, false, false, true, std::nullopt, std::nullopt, 4},    // 0 0 1 X X -> 4
    {3, true, std::nullopt, true, true, std::nullopt, 2},      // 1 x 1 1 X -> 2
    {4, true, std::nullopt, true, false, std::nullopt, 4},     // 1 x 1 0 X -> 4
    {5, false, true, false, std::nullopt, std::nullopt, 8},    // 0 1 0 X X -> 8
    {6, false, false, false, std::nullopt, std::nullopt, 16},  // 0 0 0 X X -> 16
    {7, true, std::nullopt, false, true, true, 2},             // 1 x 0 1 1 -> 2
    {8, true, std::nullopt, false, false, true, 4},            // 1 x 0 0 1 -> 4
    {9, true, std::nullopt, false, true, false, 8},            // 1 x 0 1 0 -> 8
    {10, true, std::nullopt, false, false, false, 16},         // 1 x 0 0 0 -> 16
};

class BitRateRow : public ::testing::TestWithParam<Row> {};

TEST_P(BitRateRow, PinsAndRegisterBitsGiveTheTableRate) {
  const Row& row = GetParam();
  for (bool sbaud : {false, true}) {
    if (row.sbaud && *row.sbaud != sbaud) continue;
    for (bool swbaud : {false, true}) {
      if (row.swbaud && *row.swbaud != swbaud) continue;
      for (bool swbaud16 : {false, true}) {
        if (row.swbaud16 && *row.swbaud16 != swbaud16) continue;
        ChipConfig config;
        config.sbaud = sbaud;
        config.sbaud16 = row.sbaud16;
        ChipOnBench bench(config);
        std::uint16_t sermode = 0;
        if (row.entsbaud) sermode |= kEntsbaud;
        if (swbaud) sermode |= kSwbaud;
        if (swbaud16) sermode |= kSwbaud16;
        bench.chip->reg_write(0x01, sermode);
        SCOPED_TRACE("row " + std::to_string(row.number) + " SBAUD=" + std::to_string(sbaud) +
                     " SWBAUD=" + std::to_string(swbaud) + " SWBAUD16=" + std::to_string(swbaud16));
        EXPECT_EQ(bench.chip->serial_clocks().bit_rate_hz, row.mbit * kMbit);
      }
    }
  }
}

std::string row_name(const ::testing::TestParamInfo<Row>& param_info) {
  return "row" + std::to_string(param_info.param.number);
}

INSTANTIATE_TEST_SUITE_P(DeltaSpec231, BitRateRow, ::testing::ValuesIn(kRows), row_name);

// Delta spec 2.3.1: "The chosen bit rate can be defined by pins or software": the SBAUD
// pin is live, not only sampled at reset.
TEST(BitRate, FollowsTheSbaudPinWhileRunning) {
  ChipOnBench bench;
  EXPECT_EQ(bench.chip->serial_clocks().bit_rate_hz, 16 * kMbit);  // row 6
  bench.chip->drive(Pin::SBAUD, sim::Level::High);
  EXPECT_EQ(bench.chip->serial_clocks().bit_rate_hz, 8 * kMbit);  // row 5
  bench.chip->drive(Pin::SBAUD16, sim::Level::High);
  EXPECT_EQ(bench.chip->serial_clocks().bit_rate_hz, 2 * kMbit);  // row 1
}

// Delta spec 2.3.2: in 410B-compatible mode (SBAUD16 = 1) only 2 and 4 Mbit/s exist,
// whatever SWBAUD16 says.
TEST(BitRate, CompatibleModeOffersOnlyTwoAndFour) {
  ChipConfig config;
  config.sbaud16 = true;
  for (std::uint16_t bits = 0; bits < 16; ++bits) {
    ChipOnBench bench(config);
    const auto sermode =
        static_cast<std::uint16_t>(((bits & 1u) ? kEntsbaud : 0) | ((bits & 2u) ? kSwbaud : 0) |
                                   ((bits & 4u) ? kSwbaud16 : 0));
    if (bits & 8u) bench.chip->drive(Pin::SBAUD, sim::Level::High);
    bench.chip->reg_write(0x01, sermode);
    const auto rate = bench.chip->serial_clocks().bit_rate_hz;
    EXPECT_TRUE(rate == 2 * kMbit || rate == 4 * kMbit) << rate;
    EXPECT_TRUE(bench.chip->serial_clocks().compatible_mode);
  }
}

// Facts §5: on the 410B SWBAUD = 1 means 2 Mbit/s; ENTSBAUD takes the rate from SWBAUD
// instead of the SBAUD pin. The 410B has no SWBAUD16 (delta spec 2.3.1 is 816-only).
TEST(BitRate, Sercon410BUsesSbaudOrSwbaud) {
  struct Case {
    bool sbaud;
    std::uint16_t sermode;
    std::int64_t mbit;
  };
  const Case cases[] = {
      {true, 0, 2},
      {false, 0, 4},
      {false, kEntsbaud | kSwbaud, 2},
      {true, kEntsbaud, 4},
      {true, kEntsbaud | kSwbaud16, 4},  // SWBAUD16 does not exist: ignored
  };
  for (const Case& c : cases) {
    ChipConfig config = config_410b();
    config.sbaud = c.sbaud;
    ChipOnBench bench(config);
    bench.chip->reg_write(0x01, c.sermode);
    EXPECT_EQ(bench.chip->serial_clocks().bit_rate_hz, c.mbit * kMbit);
    EXPECT_EQ(bench.chip->reg_read(0x01) & kSwbaud16, 0);
  }
}

// Delta spec 2.3.1, "SCLKO2, SCLKO4 for SCLK = 64 MHz": SBAUD16 = 1 -> 32 / 16 MHz.
TEST(ClockOutputs, Sbaud16HighGivesThirtyTwoAndSixteen) {
  ChipConfig config;
  config.sbaud16 = true;
  ChipOnBench bench(config);
  EXPECT_EQ(bench.chip->serial_clocks().sclko2_hz, 32'000'000);
  EXPECT_EQ(bench.chip->serial_clocks().sclko4_hz, 16'000'000);
}

// Same table, SBAUD16 = 0 -> 64 / 32 MHz.
TEST(ClockOutputs, Sbaud16LowGivesSixtyFourAndThirtyTwo) {
  ChipOnBench bench;
  EXPECT_EQ(bench.chip->serial_clocks().sclko2_hz, 64'000'000);
  EXPECT_EQ(bench.chip->serial_clocks().sclko4_hz, 32'000'000);
}

// Delta spec 2.3.2: in compatible mode SCLKO2/SCLKO4 give the 410B's frequencies, which
// are the SBAUD16 = 1 row (SCLK / 2, SCLK / 4; datasheet Table 1 "divided by 2 or 1").
TEST(ClockOutputs, Sercon410BDividesByTwoAndFour) {
  ChipOnBench bench(config_410b());
  EXPECT_EQ(bench.chip->serial_clocks().sclko2_hz, 32'000'000);
  EXPECT_EQ(bench.chip->serial_clocks().sclko4_hz, 16'000'000);
}

// Datasheet Table 1, OUTZ: "The clocks are turned off".
TEST(ClockOutputs, OutzTurnsEveryClockOff) {
  ChipOnBench bench;
  bench.chip->drive(Pin::OUTZ, sim::Level::High);
  EXPECT_EQ(bench.chip->serial_clocks().bit_rate_hz, 0);
  EXPECT_EQ(bench.chip->serial_clocks().sclko2_hz, 0);
  bench.chip->drive(Pin::OUTZ, sim::Level::Low);
  EXPECT_EQ(bench.chip->serial_clocks().bit_rate_hz, 16 * kMbit);
}

// The table is stated for SCLK = 64 MHz; a 32 MHz SCLK halves every clock.
TEST(ClockOutputs, OtherSclkFrequenciesScaleEveryClock) {
  SerialClockSelect s;
  s.sclk_hz = 32'000'000;
  const SerialClocks c = serial_clocks(s);
  EXPECT_EQ(c.bit_rate_hz, 8 * kMbit);
  EXPECT_EQ(c.sclko2_hz, 32'000'000);
  EXPECT_EQ(c.sclko4_hz, 16'000'000);
}

}  // namespace
}  // namespace sercon::chip

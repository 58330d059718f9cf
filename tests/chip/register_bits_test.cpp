// Key register bits checked by hand against the specification sentences, not derived
// from the table (a wrong table row would otherwise test itself).
#include <gtest/gtest.h>

#include "chip_fixture.hpp"

namespace sercon::chip {
namespace {

using testing::ChipOnBench;
using testing::config_410b;

// Delta spec 2.11.1.1: VERSION (00H) reads 0010H on the SERCON816 ...
TEST(Version, Sercon816ReadsHex0010) {
  ChipOnBench bench;
  EXPECT_EQ(bench.chip->reg_read(0x00), 0x0010);
  bench.chip->reg_write(0x00, 0x1234);  // datasheet 4.1: VERSION is R
  EXPECT_EQ(bench.chip->reg_read(0x00), 0x0010);
}

// ... and 0002H on the SERCON410B.
TEST(Version, Sercon410BReadsHex0002) {
  ChipOnBench bench(config_410b());
  EXPECT_EQ(bench.chip->reg_read(0x00), 0x0002);
}

// Delta spec 2.11.1.2: MCLKDIV 0EH.5-0 / MCLKST 0EH.13-8 on the 816,
// 0EH.4-0 / 0EH.12-8 on the 410B.
TEST(ClockDivider, Sercon816HasSixBitFields) {
  ChipOnBench bench;
  bench.chip->reg_write(0x0E, 0xFFFF);
  EXPECT_EQ(bench.chip->reg_read(0x0E), 0x3F3F);
}

TEST(ClockDivider, Sercon410BHasFiveBitFields) {
  ChipOnBench bench(config_410b());
  bench.chip->reg_write(0x0E, 0xFFFF);
  EXPECT_EQ(bench.chip->reg_read(0x0E), 0x1F1F);
}

// Delta spec 2.11.1.3: 20H bits 7-0 NDIVCLK, 8 POLDIVCLK, 9 DIVCLKMODE, 15-10 "NOT USED"
// read 0. DIVCLKMODE is an 816 addition (delta spec 2.7).
TEST(DivClkControl, Sercon816HasDivclkmode) {
  ChipOnBench bench;
  bench.chip->reg_write(0x20, 0xFFFF);
  EXPECT_EQ(bench.chip->reg_read(0x20), 0x03FF);
}

TEST(DivClkControl, Sercon410BHasNoDivclkmode) {
  ChipOnBench bench(config_410b());
  bench.chip->reg_write(0x20, 0xFFFF);
  EXPECT_EQ(bench.chip->reg_read(0x20), 0x01FF);
}

// Delta spec 2.3.1: SWBAUD16 (1H.15) is new in the 816.
TEST(SerialMode, Swbaud16OnlyOnThe816) {
  ChipOnBench b816;
  b816.chip->reg_write(0x01, 0x8000);
  EXPECT_EQ(b816.chip->reg_read(0x01) & 0x8000, 0x8000);
  ChipOnBench b410(config_410b());
  b410.chip->reg_write(0x01, 0x8000);
  EXPECT_EQ(b410.chip->reg_read(0x01) & 0x8000, 0);
}

// Facts §5: "0 RSTFL (reset flag, read back and preserved by the driver)": every reset
// sets it; the driver clears it by writing 0.
TEST(SerialMode, RstflIsSetAfterPowerOnAndClearable) {
  ChipOnBench bench;
  EXPECT_EQ(bench.chip->reg_read(0x01) & 0x0001, 0x0001);
  bench.chip->reg_write(0x01, 0x0000);
  EXPECT_EQ(bench.chip->reg_read(0x01) & 0x0001, 0);
}

// Facts §5: "1 SWRST (software reset: driver writes 0x0002)"; an action bit reads 0.
TEST(SerialMode, SwrstReadsZero) {
  ChipOnBench bench;
  bench.chip->reg_write(0x01, 0x0002);
  EXPECT_EQ(bench.chip->reg_read(0x01) & 0x0002, 0);
}

// SREGEN (1H.4) and SBAUD (1H.11) read the levels of pins 28 and 29, live (facts §5
// names; project decision on their meaning, docs/registers.md).
TEST(SerialMode, SregenAndSbaudReadThePins) {
  ChipConfig config;
  config.sbaud = true;
  config.sbaud16 = true;
  ChipOnBench bench(config);
  EXPECT_EQ(bench.chip->reg_read(0x01) & 0x0810, 0x0810);
  bench.chip->drive(Pin::SBAUD, sim::Level::Low);
  EXPECT_EQ(bench.chip->reg_read(0x01) & 0x0810, 0x0010);
  bench.chip->drive(Pin::SBAUD16, sim::Level::Low);
  EXPECT_EQ(bench.chip->reg_read(0x01) & 0x0810, 0x0000);
  bench.chip->drive(Pin::SBAUD, sim::Level::HighZ);  // internal pull-up (datasheet 3.3)
  EXPECT_EQ(bench.chip->reg_read(0x01) & 0x0810, 0x0800);
}

// Facts §5: a driver's start-up sequence writes 0x01 = REGMODE|POLTXD|ENTSBAUD|SWBAUD,
// 0x02 = 0x0383, 0x03 = 0x0100 and reads them back unchanged.
TEST(StartUp, DriverValuesReadBack) {
  ChipOnBench bench;
  bench.chip->reg_write(0x01, 0x0020 | 0x0200 | 0x0400 | 0x0040);
  EXPECT_EQ(bench.chip->reg_read(0x01) & 0x0660, 0x0660);
  bench.chip->reg_write(0x02, 0x0383);
  EXPECT_EQ(bench.chip->reg_read(0x02), 0x0383);
  bench.chip->reg_write(0x03, 0x0100);
  EXPECT_EQ(bench.chip->reg_read(0x03), 0x0100);
}

// Facts §5: "0x0D written 0xFF0A at start-up"; the project makes that the reset value.
TEST(LineMonitor, ResetValueIsWhatDriversWrite) {
  ChipOnBench bench;
  EXPECT_EQ(bench.chip->reg_read(0x0D), 0xFF0A);
}

// Facts §5: "Reading 0xFFFF means no chip": no register of a present chip reads 0xFFFF
// after reset.
TEST(Presence, NoRegisterReadsAllOnesAfterReset) {
  for (const ChipConfig& config : {ChipConfig{}, config_410b()}) {
    ChipOnBench bench(config);
    for (std::uint16_t a = 0; a <= 0x3F; ++a) EXPECT_NE(bench.chip->reg_read(a), 0xFFFF) << a;
  }
}

}  // namespace
}  // namespace sercon::chip

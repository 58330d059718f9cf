// The pin table (datasheet Table 1) and the rules for driving pins from the board.
#include "sercon/chip/pins.hpp"

#include <gtest/gtest.h>

#include <set>
#include <string>

#include "chip_fixture.hpp"

namespace sercon::chip {
namespace {

using sim::Level;
using testing::ChipOnBench;

TEST(PinTable, NamesAreUniqueAndFindable) {
  std::set<std::string> names;
  for (std::size_t i = 0; i < kPinCount; ++i) {
    const Pin p = pin_at(i);
    EXPECT_TRUE(names.insert(std::string(pin_name(p))).second) << pin_name(p);
    EXPECT_EQ(find_pin(pin_name(p)), p);
  }
  EXPECT_EQ(find_pin("NOPE"), std::nullopt);
}

// Spot checks against Table 1: pin numbers and directions.
TEST(PinTable, AgreesWithTable1) {
  EXPECT_EQ(pin_info(Pin::D15).package_pin, 77);
  EXPECT_EQ(pin_info(Pin::D0).package_pin, 95);
  EXPECT_EQ(pin_info(Pin::BUSYN).package_pin, 45);
  EXPECT_EQ(pin_info(Pin::BUSYN).direction, PinDirection::Out);
  EXPECT_EQ(pin_info(Pin::TxD6).package_pin, 22);
  EXPECT_EQ(pin_info(Pin::TxD2).package_pin, 17);
  EXPECT_EQ(pin_info(Pin::SBAUD16).package_pin, 28);
  EXPECT_EQ(pin_info(Pin::WDOGN).package_pin, 24);             // delta spec 2.2: was TxDNRZ
  EXPECT_EQ(pin_info(Pin::TxC).direction, PinDirection::Out);  // delta spec 2.2: O, not I/O
  EXPECT_EQ(pin_info(Pin::RxC).direction, PinDirection::Out);
  EXPECT_EQ(pin_info(Pin::CYC_CLK).direction, PinDirection::In);
  EXPECT_EQ(pin_info(Pin::D7).direction, PinDirection::InOut);
  EXPECT_EQ(pin_info(Pin::RSTN).pull, Pull::Down);  // datasheet 3.3
  EXPECT_EQ(pin_info(Pin::OUTZ).pull, Pull::Up);
  EXPECT_EQ(kPinCount, 81u);  // D15-0, A15-0 and the 49 other signals of Table 1
}

TEST(PinDrive, BoardCannotDriveOutputs) {
  ChipOnBench bench;
  EXPECT_THROW(bench.chip->drive(Pin::INT0, Level::High), std::invalid_argument);
  EXPECT_THROW(bench.chip->drive(Pin::NDTRO, Level::Low), std::invalid_argument);
}

TEST(PinDrive, ClocksAreFrequenciesAndTestIsTiedLow) {
  ChipOnBench bench;
  EXPECT_THROW(bench.chip->drive(Pin::MCLK, Level::High), std::invalid_argument);
  EXPECT_THROW(bench.chip->drive(Pin::SCLK, Level::High), std::invalid_argument);
  EXPECT_THROW(bench.chip->drive(Pin::TEST, Level::High), std::invalid_argument);
  EXPECT_THROW(bench.chip->drive(Pin::TEST, Level::HighZ), std::invalid_argument);  // pull-up
  EXPECT_NO_THROW(bench.chip->drive(Pin::TEST, Level::Low));
}

// Datasheet 3.3 lists no pull resistor for RDN, WRN and BUSWIDTH: they must be driven.
TEST(PinDrive, PinsWithoutPullCannotFloat) {
  ChipOnBench bench;
  EXPECT_THROW(bench.chip->drive(Pin::RDN, Level::HighZ), std::invalid_argument);
  EXPECT_THROW(bench.chip->drive(Pin::BUSWIDTH, Level::HighZ), std::invalid_argument);
  EXPECT_NO_THROW(bench.chip->drive(Pin::CYC_CLK, Level::HighZ));
  EXPECT_TRUE(bench.chip->input_high(Pin::CYC_CLK));
}

// NDTRO: a NAND tree over the inputs (order: Pin order, project decision). Any single
// input change flips the tree's output when every later input is 1.
TEST(NandTree, LastInputFlipsTheOutput) {
  ChipOnBench bench;
  Chip& chip = *bench.chip;
  // OUTZ is the last tree input; when it is 0 the last NAND gives 1.
  EXPECT_EQ(chip.pin(Pin::NDTRO).level(), Level::High);
  chip.drive(Pin::OUTZ, Level::High);  // NAND(t, 1) = !t
  const Level with_outz = chip.pin(Pin::NDTRO).level();
  EXPECT_NE(with_outz, Level::HighZ);  // Table 1: NDTRO is not set to high impedance
  chip.drive(Pin::TEST, Level::Low);   // unchanged input: unchanged output
  EXPECT_EQ(chip.pin(Pin::NDTRO).level(), with_outz);
}

// The kept stages give the same NDTRO as evaluating the whole chain after every change.
TEST(NandTree, MatchesAFullEvaluation) {
  ChipOnBench bench;
  Chip& chip = *bench.chip;
  auto full = [&chip] {
    bool started = false;
    bool t = false;
    for (std::size_t i = 0; i < kPinCount; ++i) {
      const Pin p = pin_at(i);
      if (pin_info(p).direction == PinDirection::Out) continue;
      t = started ? !(t && chip.input_high(p)) : chip.input_high(p);
      started = true;
    }
    return t;
  };
  const Pin toggles[] = {Pin::D0,  Pin::A3,  Pin::TM1,   Pin::D0,   Pin::CYC_CLK, Pin::RxD,
                         Pin::A15, Pin::D15, Pin::SBAUD, Pin::BHEN, Pin::A0,      Pin::OUTZ,
                         Pin::RxD, Pin::D7,  Pin::OUTZ,  Pin::A3,   Pin::ADMUX,   Pin::ADMUX};
  for (Pin p : toggles) {
    chip.drive(p, chip.input_high(p) ? Level::Low : Level::High);
    EXPECT_EQ(chip.pin(Pin::NDTRO).level(), sim::level_of(full())) << pin_name(p);
  }
}

}  // namespace
}  // namespace sercon::chip

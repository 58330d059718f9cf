// Config validation: clock ranges of datasheet 3.2 / 3.5.1 / 3.5.2, exact picosecond
// periods (architecture guide: integer time), and the modes the model does not build.
#include "sercon/chip/chip_config.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <stdexcept>

#include "chip_fixture.hpp"

namespace sercon::chip {
namespace {

using ::testing::HasSubstr;

std::string problem(const ChipConfig& c) {
  try {
    c.validate();
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

TEST(ChipConfig, DefaultIsValid) { EXPECT_EQ(problem(ChipConfig{}), ""); }

// Datasheet 3.5.1: f_MCLK 12..64 MHz.
TEST(ChipConfig, MclkRange) {
  ChipConfig c;
  for (std::int64_t ok : {12'500'000, 16'000'000, 20'000'000, 25'000'000, 40'000'000, 64'000'000}) {
    c.mclk_hz = ok;
    EXPECT_EQ(problem(c), "") << ok;
  }
  c.mclk_hz = 10'000'000;
  EXPECT_THAT(problem(c), HasSubstr("outside 12..64 MHz"));
  c.mclk_hz = 80'000'000;
  EXPECT_THAT(problem(c), HasSubstr("outside 12..64 MHz"));
}

// Every MCLK in range is accepted, also those without a whole-picosecond period: edge k is
// at floor(k * 1e12 / f_MCLK) ps (MclkGrid), e.g. the datasheet's 12 MHz minimum (83 333.3 ps).
TEST(ChipConfig, MclkNeedsNoExactPeriod) {
  ChipConfig c;
  for (std::int64_t inexact :
       {12'000'000, 24'000'000, 30'000'000, 33'000'000, 48'000'000, 60'000'000, 12'000'001}) {
    c.mclk_hz = inexact;
    EXPECT_EQ(problem(c), "") << inexact;
  }
}

// Datasheet 3.5.2: SCLK at most 64 MHz; at least 32 MHz when the PLL is used (SBAUD16=0).
TEST(ChipConfig, SclkRange) {
  ChipConfig c;
  c.sclk_hz = 128'000'000;
  EXPECT_THAT(problem(c), HasSubstr("SCLK"));
  c.sclk_hz = 16'000'000;
  EXPECT_THAT(problem(c), HasSubstr("minimum with the PLL on"));
  c.sbaud16 = true;
  EXPECT_EQ(problem(c), "");
  c.sclk_hz = 60'000'000;  // 15 Mbit/s at SCLK / 4: 66 666.6 ps bits
  EXPECT_THAT(problem(c), HasSubstr("whole-picosecond"));
}

// Delta spec 2.3.2: a 410B without internal clock recovery (SREGEN = 0) is not modelled.
TEST(ChipConfig, Sercon410BNeedsSregenHigh) {
  ChipConfig c;
  c.variant = Variant::Sercon410B;
  c.sbaud16 = false;
  EXPECT_THAT(problem(c), HasSubstr("SREGEN"));
}

TEST(ChipConfig, ChipRefusesABadConfig) {
  sim::Scheduler s;
  ChipConfig c;
  c.mclk_hz = 0;
  EXPECT_THROW(Chip(s, c), std::invalid_argument);
}

// Runtime checks of the same rules when a board drives the strap pins.
TEST(ChipConfig, DrivingStrapsKeepsTheRules) {
  ChipConfig c;
  c.sbaud16 = true;
  c.sclk_hz = 16'000'000;
  testing::ChipOnBench bench(c);
  EXPECT_THROW(bench.chip->drive(Pin::SBAUD16, sim::Level::Low), std::invalid_argument);
  testing::ChipOnBench b410(testing::config_410b());
  EXPECT_THROW(b410.chip->drive(Pin::SBAUD16, sim::Level::Low), std::invalid_argument);
}

}  // namespace
}  // namespace sercon::chip

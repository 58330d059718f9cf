// Requirement: --rate takes the four SERCOS rates, 2/4/8/16 Mbit/s (sercos-facts §1), and
// names any other rate as impossible.
#include "bit_rate.hpp"

#include <gtest/gtest.h>

#include "input_error.hpp"

namespace sercon::tools {
namespace {

TEST(BitRate, TheFourSercosRates) {
  EXPECT_EQ(parse_bit_rate("2M"), 500'000);
  EXPECT_EQ(parse_bit_rate("4M"), 250'000);
  EXPECT_EQ(parse_bit_rate("8m"), 125'000);
  EXPECT_EQ(parse_bit_rate("16M"), 62'500);
  EXPECT_EQ(parse_bit_rate("16Mbit/s"), 62'500);
  EXPECT_EQ(parse_bit_rate("4000000"), 250'000);
}

TEST(BitRate, OthersAreImpossible) {
  for (const char* text : {"3M", "1M", "32M", "4", "4k", "", "M", "4.0M", "16 M"}) {
    EXPECT_THROW(parse_bit_rate(text), InputError) << text;
  }
}

TEST(BitRate, Descriptions) {
  EXPECT_EQ(describe_bit_period(62'500), "16 Mbit/s");
  EXPECT_EQ(describe_bit_period(500'000), "2 Mbit/s");
  EXPECT_EQ(bits_per_second(250'000), 4'000'000);
}

}  // namespace
}  // namespace sercon::tools

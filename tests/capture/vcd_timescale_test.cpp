// Requirement: the VCD reader accepts $timescale with every unit s..fs and 1/10/100, and
// rejects what picoseconds cannot represent (docs/decode.md "VCD").
#include "sercon/capture/vcd_timescale.hpp"

#include <gtest/gtest.h>

#include "sercon/capture/capture_error.hpp"

namespace sercon::capture {
namespace {

TEST(VcdTimescale, EveryUnitFromSecondsToPicoseconds) {
  EXPECT_EQ(parse_vcd_timescale_ps("1 s"), 1'000'000'000'000);
  EXPECT_EQ(parse_vcd_timescale_ps("100 ms"), 100'000'000'000);
  EXPECT_EQ(parse_vcd_timescale_ps("10 us"), 10'000'000);
  EXPECT_EQ(parse_vcd_timescale_ps("1 ns"), 1'000);
  EXPECT_EQ(parse_vcd_timescale_ps("10 ns"), 10'000);
  EXPECT_EQ(parse_vcd_timescale_ps("100 ps"), 100);
  EXPECT_EQ(parse_vcd_timescale_ps("1 ps"), 1);
}

TEST(VcdTimescale, NumberAndUnitMayBeJoinedOrSpread) {
  EXPECT_EQ(parse_vcd_timescale_ps("1ns"), 1'000);
  EXPECT_EQ(parse_vcd_timescale_ps("  100\tus "), 100'000'000);
}

TEST(VcdTimescale, FemtosecondsAreRejectedAsFinerThanAPicosecond) {
  for (const char* text : {"1 fs", "10 fs", "100 fs"}) {
    try {
      parse_vcd_timescale_ps(text);
      FAIL() << text;
    } catch (const CaptureError& e) {
      EXPECT_NE(std::string(e.what()).find("finer than 1 ps"), std::string::npos) << e.what();
    }
  }
}

TEST(VcdTimescale, OtherNumbersAndUnitsAreRejected) {
  for (const char* text : {"2 ns", "1000 ps", "0 ns", "ns", "1 min", "1 NS", "", "1.0 ns"}) {
    EXPECT_THROW(parse_vcd_timescale_ps(text), CaptureError) << text;
  }
}

}  // namespace
}  // namespace sercon::capture

// Requirement: `--format` defaults from the file's extension (issue "sercon decode").
#include "sercon/capture/capture_format.hpp"

#include <gtest/gtest.h>

#include "sercon/capture/capture_error.hpp"

namespace sercon::capture {
namespace {

TEST(CaptureFormat, FromTheExtension) {
  EXPECT_EQ(format_from_extension("a/b/line.bits"), CaptureFormat::Bits);
  EXPECT_EQ(format_from_extension("dump.BIN"), CaptureFormat::Bits);
  EXPECT_EQ(format_from_extension("x.vcd"), CaptureFormat::Vcd);
  EXPECT_EQ(format_from_extension("x.Sr"), CaptureFormat::Sr);
}

TEST(CaptureFormat, UnknownOrMissingExtensionSaysUseFormat) {
  for (const char* name : {"capture.txt", "capture"}) {
    try {
      format_from_extension(name);
      FAIL() << name;
    } catch (const CaptureError& e) {
      EXPECT_NE(std::string(e.what()).find("--format bits|vcd|sr"), std::string::npos) << e.what();
    }
  }
}

TEST(CaptureFormat, NamesRoundTrip) {
  for (CaptureFormat f : {CaptureFormat::Bits, CaptureFormat::Vcd, CaptureFormat::Sr}) {
    EXPECT_EQ(parse_format(format_name(f)), f);
  }
  EXPECT_FALSE(parse_format("csv").has_value());
}

}  // namespace
}  // namespace sercon::capture

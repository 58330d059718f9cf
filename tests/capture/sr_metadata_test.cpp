// Requirement: the sigrok session metadata (INI) as sigrok writes it: [device 1] with
// samplerate ("64 MHz", "1000000"), total probes, probeN, unitsize, capturefile
// (issue "capture readers", sr).
#include "sercon/capture/sr_metadata.hpp"

#include <gtest/gtest.h>

#include "sercon/capture/capture_error.hpp"

namespace sercon::capture {
namespace {

std::string error_of(std::string_view text) {
  try {
    parse_sr_metadata(text);
  } catch (const CaptureError& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(SrSamplerate, UnitsAsSigrokPrintsThem) {
  EXPECT_EQ(parse_samplerate("64 MHz"), 64'000'000U);
  EXPECT_EQ(parse_samplerate("200 kHz"), 200'000U);
  EXPECT_EQ(parse_samplerate("1 GHz"), 1'000'000'000U);
  EXPECT_EQ(parse_samplerate("12345 Hz"), 12'345U);
  EXPECT_EQ(parse_samplerate("1000000"), 1'000'000U);
  EXPECT_EQ(parse_samplerate("1.5 MHz"), 1'500'000U);
  EXPECT_EQ(parse_samplerate("24MHz"), 24'000'000U);
  EXPECT_EQ(parse_samplerate("10 k"), 10'000U);
}

TEST(SrSamplerate, NonsenseIsRejected) {
  for (const char* text :
       {"", "fast", "0 Hz", "1.5 Hz", "-1 MHz", "1. MHz", "1e6", "2 THz", "99999999999 GHz"}) {
    EXPECT_THROW(parse_samplerate(text), CaptureError) << text;
  }
}

TEST(SrMetadata, WhatSigrokCliWritesForTheDemoDevice) {
  const SrMetadata meta = parse_sr_metadata(
      "[global]\nsigrok version=0.5.2\n\n[device 1]\ncapturefile=logic-1\ntotal probes=8\n"
      "samplerate=200 kHz\ntotal analog=0\nprobe1=D0\nunitsize=1\n");
  EXPECT_EQ(meta.capturefile, "logic-1");
  EXPECT_EQ(meta.samplerate_hz, 200'000U);
  EXPECT_EQ(meta.total_probes, 8U);
  EXPECT_EQ(meta.unitsize, 1U);
  ASSERT_EQ(meta.probes.size(), 1U);
  EXPECT_EQ(meta.probes[0].number, 1U);
  EXPECT_EQ(meta.probes[0].name, "D0");
}

TEST(SrMetadata, ProbesAreSortedByNumberAndMayHaveGaps) {
  const SrMetadata meta = parse_sr_metadata(
      "[device 1]\ncapturefile=logic-1\ntotal probes=16\nsamplerate=1 MHz\nunitsize=2\n"
      "probe12=RX\nprobe3=TX\n; comment\n# another\n");
  ASSERT_EQ(meta.probes.size(), 2U);
  EXPECT_EQ(meta.probes[0].number, 3U);
  EXPECT_EQ(meta.probes[1].name, "RX");
}

TEST(SrMetadata, ProblemsAreNamed) {
  const std::string device = "[device 1]\ncapturefile=logic-1\nsamplerate=1 MHz\n";
  EXPECT_NE(error_of("[global]\nx=1\n").find("no [device 1]"), std::string::npos);
  EXPECT_NE(error_of("[device 1]\nsamplerate=1 MHz\n").find("no logic data"), std::string::npos);
  EXPECT_NE(error_of("[device 1]\ncapturefile=logic-1\n").find("no 'samplerate'"),
            std::string::npos);
  EXPECT_NE(error_of(device + "total probes=1\nprobe1=D0\n").find("no 'unitsize'"),
            std::string::npos);
  EXPECT_NE(error_of(device + "unitsize=1\nprobe1=D0\n").find("no 'total probes'"),
            std::string::npos);
  EXPECT_NE(error_of(device + "unitsize=0\ntotal probes=1\n").find("unitsize is 0"),
            std::string::npos);
  EXPECT_NE(error_of(device + "unitsize=1\ntotal probes=9\nprobe9=D8\n").find("does not fit"),
            std::string::npos);
  EXPECT_NE(error_of(device + "unitsize=1\ntotal probes=2\nprobe3=D2\n").find("does not fit"),
            std::string::npos);
  EXPECT_NE(error_of(device + "unitsize=1\ntotal probes=0\n").find("no logic probes"),
            std::string::npos);
  EXPECT_NE(error_of(device + "unitsize=one\n").find("bad unitsize"), std::string::npos);
  EXPECT_NE(error_of("[device 1\n").find("unterminated section"), std::string::npos);
  EXPECT_NE(error_of("key=value\n").find("inside a [section]"), std::string::npos);
}

}  // namespace
}  // namespace sercon::capture

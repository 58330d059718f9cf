// Requirement: the repository ships captures/phase-up-4drives.bits (a four-drive ring
// phasing up at 4 Mbit/s with one bad FCS) and sigrok-made .sr/.vcd excerpts, described
// in captures/README.md; `sercon decode` reads them (scripts/main runs the first).
#include <gtest/gtest.h>

#include "run_sercon.hpp"

namespace sercon::testing {
namespace {

std::string capture(const char* name) { return source_dir() + "/captures/" + name; }

TEST(SampleCapture, PhaseUpDecodesAsDescribed) {
  const RunResult r =
      run_sercon({"decode", "--json", "--rate", "4M", capture("phase-up-4drives.bits")});
  ASSERT_EQ(r.status, 0) << r.err;
  const auto lines = json_lines(r.out);
  ASSERT_FALSE(lines.empty());
  const nlohmann::json& s = lines.back().at("summary");
  // captures/README.md: CP0 x10, CP1 x8, CP2 x9, CP3 x8, CP4 x16 cycles.
  EXPECT_EQ(s.at("kinds").at("MST"), 51);
  EXPECT_EQ(s.at("kinds").at("AT/MDT"), 28);  // CP1: 8 MDT + 4 AT, CP2: 8 MDT + 8 AT
  EXPECT_EQ(s.at("kinds").at("MDT"), 24);     // CP3 + CP4 broadcast MDTs
  EXPECT_EQ(s.at("kinds").at("AT"), 95);      // 4 per CP3/CP4 cycle, one corrupted
  EXPECT_EQ(s.at("fcs_errors"), 1);
  EXPECT_EQ(s.at("error_count"), 1);
  EXPECT_EQ(s.at("phases"), nlohmann::json({0, 1, 2, 3, 4}));
  EXPECT_LT(std::filesystem::file_size(capture("phase-up-4drives.bits")), 100'000U);

  // The corrupted telegram: drive 3's AT in CP4 cycle 10.
  std::size_t bad = 0;
  for (const auto& line : lines) {
    if (line.contains("error")) {
      ++bad;
      EXPECT_EQ(line.at("error"), "bad_fcs");
      EXPECT_EQ(line.at("address"), 3);
      EXPECT_EQ(line.at("kind"), "AT");
    }
  }
  EXPECT_EQ(bad, 1U);
}

TEST(SampleCapture, SigrokExcerptsDecodeAlike) {
  std::vector<nlohmann::json> first;
  for (const char* name : {"cp4-excerpt.sr", "cp4-excerpt.vcd"}) {
    SCOPED_TRACE(name);
    const RunResult r = run_sercon({"decode", "--json", capture(name)});
    ASSERT_EQ(r.status, 0) << r.err;
    const auto lines = json_lines(r.out);
    const nlohmann::json& s = lines.back().at("summary");
    EXPECT_EQ(s.at("telegrams"), 12);
    EXPECT_EQ(s.at("kinds").at("AT"), 8);
    EXPECT_EQ(s.at("error_count"), 0);
    EXPECT_EQ(s.at("bit_rate"), 4'000'000);
    EXPECT_EQ(s.at("rate_source"), "detected");
    if (first.empty()) {
      first = lines;
      continue;
    }
    ASSERT_EQ(lines.size(), first.size());
    for (std::size_t i = 0; i + 1 < lines.size(); ++i) {
      EXPECT_EQ(lines[i].at("data"), first[i].at("data"));
      // VCD edges sit on sample boundaries, sample-based recovery halfway between samples.
      EXPECT_NEAR(lines[i].at("t_ns").get<double>(), first[i].at("t_ns").get<double>(), 25.0);
    }
  }
}

}  // namespace
}  // namespace sercon::testing

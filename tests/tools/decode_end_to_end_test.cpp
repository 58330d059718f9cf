// Requirement: `sercon decode` round trips (issue "sercon decode", Tests): telegrams from
// the wire encoder -> bits / VCD / sr file -> the real binary -> text and JSON with the
// right kinds, phases, addresses, data and times (from bit positions x bit period), every
// error class reported with exit status 0, and the summary. Kinds: docs/decode.md.
#include <gtest/gtest.h>

#include <cmath>

#include "run_sercon.hpp"
#include "sercon/wire/encoder.hpp"
#include "test_files.hpp"
#include "test_lines.hpp"

namespace sercon::testing {
namespace {

struct Rate {
  const char* name;
  std::int64_t period_ps;
};
constexpr Rate kRates[] = {{"2M", 500'000}, {"4M", 250'000}, {"8M", 125'000}, {"16M", 62'500}};

// Checks JSON rows against the frames the line was built with. Times: start_bit x period
// from the capture start, within `tolerance_ps` (0 for bits and exact VCD edges).
void expect_rows(const std::vector<nlohmann::json>& lines, const TestLine& line,
                 std::int64_t period_ps, double tolerance_ps) {
  ASSERT_EQ(lines.size(), line.frames.size() + 1) << "one line per frame, then the summary";
  for (std::size_t i = 0; i < line.frames.size(); ++i) {
    const ExpectedFrame& f = line.frames[i];
    const nlohmann::json& row = lines[i];
    SCOPED_TRACE("frame " + std::to_string(i) + ": " + row.dump());
    const double t_ns =
        static_cast<double>(static_cast<std::int64_t>(f.start_bit) * period_ps) / 1000.0;
    EXPECT_NEAR(row.at("t_ns").get<double>(), t_ns, tolerance_ps / 1000.0);
    EXPECT_EQ(row.at("address").get<int>(), f.address);
    EXPECT_EQ(row.at("data").get<std::string>(), hex(f.data));
    EXPECT_EQ(row.at("length").get<std::size_t>(), f.data.size());
    if (f.error.empty()) {
      EXPECT_FALSE(row.contains("error"));
      EXPECT_EQ(row.at("kind").get<std::string>(), f.kind);
      EXPECT_TRUE(row.at("fcs_ok").get<bool>());
    } else {
      EXPECT_EQ(row.at("error").get<std::string>(), f.error);
      if (f.error == "bad_fcs") {
        EXPECT_EQ(row.at("kind").get<std::string>(), f.kind);
        EXPECT_FALSE(row.at("fcs_ok").get<bool>());
      } else {
        EXPECT_FALSE(row.contains("kind"));  // not a whole telegram
      }
    }
    if (f.phase && f.error.empty()) {
      EXPECT_EQ(row.at("phase").get<unsigned>(), *f.phase);
      EXPECT_EQ(row.at("phase_valid").get<bool>(), *f.phase <= 4);
    }
    if (f.kind != "MST") {
      EXPECT_FALSE(row.contains("phase"));
    }
  }
}

void expect_phase_walk_summary(const nlohmann::json& summary, std::int64_t period_ps) {
  EXPECT_EQ(summary.at("telegrams").get<int>(), 17);
  EXPECT_EQ(summary.at("kinds").at("MST").get<int>(), 7);
  EXPECT_EQ(summary.at("kinds").at("MDT").get<int>(), 1);
  EXPECT_EQ(summary.at("kinds").at("AT").get<int>(), 5);
  EXPECT_EQ(summary.at("kinds").at("AT/MDT").get<int>(), 3);
  EXPECT_EQ(summary.at("kinds").at("ADDR0").get<int>(), 1);
  EXPECT_EQ(summary.at("fcs_errors").get<int>(), 0);
  EXPECT_EQ(summary.at("error_count").get<int>(), 0);
  EXPECT_EQ(summary.at("phases"), nlohmann::json({0, 1, 2, 3, 4, 5, 4}));
  EXPECT_EQ(summary.at("bit_period_ps").get<std::int64_t>(), period_ps);
  EXPECT_EQ(summary.at("bit_rate").get<std::int64_t>(), 1'000'000'000'000 / period_ps);
}

TEST(DecodeEndToEnd, BitsAtEveryRateJson) {
  const TestLine line = phase_walk_line();
  TempDir dir;
  write_file(dir / "walk.bits", std::string(line.bits.packed().begin(), line.bits.packed().end()));
  for (const Rate& rate : kRates) {
    SCOPED_TRACE(rate.name);
    const RunResult r =
        run_sercon({"decode", "--json", "--rate", rate.name, (dir / "walk.bits").string()});
    ASSERT_EQ(r.status, 0) << r.err;
    const auto lines = json_lines(r.out);
    expect_rows(lines, line, rate.period_ps, 0);
    const nlohmann::json& summary = lines.back().at("summary");
    expect_phase_walk_summary(summary, rate.period_ps);
    EXPECT_EQ(summary.at("rate_source"), "option");
    EXPECT_EQ(summary.at("format"), "bits");
  }
}

TEST(DecodeEndToEnd, BitsText) {
  const TestLine line = phase_walk_line();
  TempDir dir;
  write_file(dir / "walk.bin", std::string(line.bits.packed().begin(), line.bits.packed().end()));
  const RunResult r = run_sercon({"decode", "--rate", "4M", (dir / "walk.bin").string()});
  ASSERT_EQ(r.status, 0) << r.err;
  const auto t = [&](std::size_t i) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%12.1f", static_cast<double>(line.frames[i].start_bit) * 250.0);
    return std::string(buf);
  };
  EXPECT_NE(r.out.find(t(1) + "  MST      255     1  data=00 fcs=ok phase=0\n"), std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find(t(5) + "  AT/MDT     2     4  data=01000000 fcs=ok\n"), std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find(t(6) + "  ADDR0      0     2  data=aa55 fcs=ok\n"), std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("data=05 fcs=ok phase=5 (invalid: above 4)"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("data=0c fcs=ok phase=4\n"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("  telegrams  17 (MST 7, MDT 1, AT 5, AT/MDT 3, ADDR0 1)\n"),
            std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("  errors     0\n"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("  phases     0 -> 1 -> 2 -> 3 -> 4 -> 5 (invalid) -> 4\n"),
            std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("  bit rate   4 Mbit/s (from --rate)\n"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("legend     AT/MDT = addressed telegram in CP1/CP2"), std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("legend     ADDR0 = address 0"), std::string::npos) << r.out;
}

TEST(DecodeEndToEnd, VcdWithDetectedRateAndExactTimes) {
  const TestLine line = phase_walk_line();
  TempDir dir;
  for (const Rate& rate : kRates) {
    SCOPED_TRACE(rate.name);
    write_file(dir / "walk.vcd", vcd_for_line(line.bits, rate.period_ps, 1));
    const RunResult r = run_sercon({"decode", "--json", (dir / "walk.vcd").string()});
    ASSERT_EQ(r.status, 0) << r.err;
    const auto lines = json_lines(r.out);
    expect_rows(lines, line, rate.period_ps, 0);
    const nlohmann::json& summary = lines.back().at("summary");
    expect_phase_walk_summary(summary, rate.period_ps);
    EXPECT_EQ(summary.at("rate_source"), "detected");
    EXPECT_EQ(summary.at("signal"), "top.rx");
  }
}

TEST(DecodeEndToEnd, VcdInNanosecondsWithGivenRate) {
  const TestLine line = phase_walk_line();
  TempDir dir;
  write_file(dir / "walk.vcd", vcd_for_line(line.bits, 500'000, 1000));
  const RunResult r = run_sercon(
      {"decode", "--json", "--rate", "2M", "--signal", "rx", (dir / "walk.vcd").string()});
  ASSERT_EQ(r.status, 0) << r.err;
  expect_rows(json_lines(r.out), line, 500'000, 0);
}

TEST(DecodeEndToEnd, SigrokSessionWithinOneSample) {
  const TestLine line = phase_walk_line();
  TempDir dir;
  // 10 samples per bit at every rate; the session names its samplerate like sigrok does.
  const std::pair<Rate, const char*> cases[] = {
      {kRates[0], "20 MHz"}, {kRates[1], "40 MHz"}, {kRates[2], "80 MHz"}, {kRates[3], "160 MHz"}};
  for (const auto& [rate, samplerate] : cases) {
    SCOPED_TRACE(rate.name);
    write_sr(dir / "walk.sr", sr_metadata(samplerate, {"RX"}), oversample(line.bits, 10));
    const RunResult r = run_sercon({"decode", "--json", (dir / "walk.sr").string()});
    ASSERT_EQ(r.status, 0) << r.err;
    const auto lines = json_lines(r.out);
    expect_rows(lines, line, rate.period_ps, static_cast<double>(rate.period_ps) / 10);
    expect_phase_walk_summary(lines.back().at("summary"), rate.period_ps);
  }
}

// Brief (sample rates that are not a whole number of ps): a 24 MHz session (41 666.67 ps a
// sample, the fx2lafw logic analyzers' rate) of 0.2 s at 4 Mbit/s. The telegram at the end
// has the time of its encoder bit position to within one sample; a period rounded to
// 41 667 ps would put it 1.6 us late.
TEST(DecodeEndToEnd, SigrokSessionAt24MHzKeepsTimesToTheEnd) {
  wire::LineEncoder enc(true);
  enc.idle(32);
  const std::vector<std::uint8_t> mst{0x04};
  const std::size_t first = enc.telegram(0xFF, mst).start_bit;
  enc.idle(800'000);  // 0.2 s of fill
  const std::size_t last = enc.telegram(0xFF, mst).start_bit;
  enc.idle(64);
  TempDir dir;
  write_sr(dir / "fx2.sr", sr_metadata("24 MHz", {"D0"}), oversample(enc.bits(), 6), 1 << 20);
  const RunResult r = run_sercon({"decode", "--json", "--rate", "4M", (dir / "fx2.sr").string()});
  ASSERT_EQ(r.status, 0) << r.err;
  const auto lines = json_lines(r.out);
  ASSERT_EQ(lines.size(), 3u) << r.out;
  const double sample_ns = 1e9 / 24e6;
  EXPECT_NEAR(lines[0].at("t_ns").get<double>(), static_cast<double>(first) * 250.0, sample_ns);
  EXPECT_NEAR(lines[1].at("t_ns").get<double>(), static_cast<double>(last) * 250.0, sample_ns);
  EXPECT_EQ(lines[1].at("start_bit").get<std::size_t>(), last);
}

TEST(DecodeEndToEnd, SigrokSessionChannelOfSeveral) {
  const TestLine line = phase_walk_line();
  TempDir dir;
  write_sr(dir / "walk.sr", sr_metadata("40 MHz", {"CLK", "TX", "RX"}),
           oversample(line.bits, 10, 1, 2));
  const RunResult r = run_sercon(
      {"decode", "--json", "--signal", "RX", "--rate", "4M", (dir / "walk.sr").string()});
  ASSERT_EQ(r.status, 0) << r.err;
  expect_rows(json_lines(r.out), line, 250'000, 25'000);
}

TEST(DecodeEndToEnd, EveryErrorClassIsReportedAndExitsZero) {
  const TestLine line = error_line();
  TempDir dir;
  write_file(dir / "errors.bits",
             std::string(line.bits.packed().begin(), line.bits.packed().end()));
  const RunResult json =
      run_sercon({"decode", "--json", "--rate", "8M", (dir / "errors.bits").string()});
  ASSERT_EQ(json.status, 0) << json.err;
  const auto lines = json_lines(json.out);
  expect_rows(lines, line, 125'000, 0);
  const nlohmann::json& summary = lines.back().at("summary");
  EXPECT_EQ(summary.at("telegrams").get<int>(), 3);
  EXPECT_EQ(summary.at("fcs_errors").get<int>(), 2);
  EXPECT_EQ(summary.at("error_count").get<int>(), 6);
  EXPECT_EQ(
      summary.at("errors"),
      nlohmann::json(
          {{"bad_fcs", 2}, {"abort", 1}, {"too_short", 1}, {"misaligned", 1}, {"truncated", 1}}));
  EXPECT_EQ(summary.at("phases"), nlohmann::json({4}));  // the bad-FCS MST announced none

  const RunResult text = run_sercon({"decode", "--rate", "8M", (dir / "errors.bits").string()});
  ASSERT_EQ(text.status, 0) << text.err;
  for (const char* cls :
       {"error=bad-fcs", "error=abort", "error=too-short", "error=misaligned", "error=truncated"}) {
    EXPECT_NE(text.out.find(cls), std::string::npos) << cls << "\n" << text.out;
  }
  EXPECT_NE(text.out.find("  errors     6 (bad-fcs 2, abort 1, too-short 1, misaligned 1, "
                          "truncated 1)\n"),
            std::string::npos)
      << text.out;
}

TEST(DecodeEndToEnd, SigrokCliMadeSessionAndVcd) {
  const std::string tool = sigrok_cli();
  if (tool.empty()) GTEST_SKIP() << "sigrok-cli not installed";
  const TestLine line = phase_walk_line();
  TempDir dir;
  write_file(dir / "walk.bin", oversample(line.bits, 8));
  const std::string input =
      " -I binary:numchannels=1:samplerate=64000000 -i " + shell_quote((dir / "walk.bin").string());
  ASSERT_EQ(run_command(shell_quote(tool) + input + " -o " +
                        shell_quote((dir / "walk.sr").string()) + " >/dev/null 2>&1"),
            0);
  ASSERT_EQ(run_command(shell_quote(tool) + input + " -O vcd -o " +
                        shell_quote((dir / "walk.vcd").string()) + " >/dev/null 2>&1"),
            0);
  for (const char* file : {"walk.sr", "walk.vcd"}) {
    SCOPED_TRACE(file);
    const RunResult r = run_sercon({"decode", "--json", (dir / file).string()});
    ASSERT_EQ(r.status, 0) << r.err;
    const auto lines = json_lines(r.out);
    // 8 Mbit/s at 64 MHz; sigrok's VCD rounds times to 100 ps.
    expect_rows(lines, line, 125'000, 15'625 + 100);
    expect_phase_walk_summary(lines.back().at("summary"), 125'000);
  }
}

}  // namespace
}  // namespace sercon::testing

// Requirement: the text and JSON output formats of docs/decode.md: one line per telegram
// (time ns, kind, address, length, data hex, FCS status, phase of MSTs), errors with their
// class, JSON keys t_ns/kind/address/data/fcs_ok/phase/error, summary last.
#include <gtest/gtest.h>

#include "json_output.hpp"
#include "text_output.hpp"

namespace sercon::tools {
namespace {

TelegramRow mst(unsigned phase) {
  TelegramRow row;
  row.t_ps = 1'234'500;
  row.kind = TelegramKind::Mst;
  row.address = 255;
  row.data = {static_cast<std::uint8_t>(phase)};
  row.fcs_ok = true;
  row.phase = phase;
  row.start_bit = 10;
  row.end_bit = 60;
  return row;
}

DecodeRunInfo info() {
  DecodeRunInfo i;
  i.file = "x.bits";
  i.bit_period_ps = 250'000;
  i.rate_given = true;
  i.line_bits = 4000;
  return i;
}

TEST(TextOutput, TelegramLine) {
  EXPECT_EQ(text_row(mst(2)), "      1234.5  MST      255     1  data=02 fcs=ok phase=2");
  EXPECT_EQ(text_row(mst(6)),
            "      1234.5  MST      255     1  data=06 fcs=ok phase=6 (invalid: above 4)");
}

TEST(TextOutput, BadFcsLineShowsBothFcs) {
  TelegramRow row;
  row.t_ps = 62'500;
  row.kind = TelegramKind::AtOrMdt;
  row.address = 3;
  row.data = {0x01, 0x00, 0xab, 0xcd};
  row.fcs_ok = false;
  row.fcs_received = 0x1234;
  row.fcs_computed = 0xBEEF;
  row.error = ErrorClass::BadFcs;
  EXPECT_EQ(text_row(row),
            "        62.5  AT/MDT     3     4  data=0100abcd fcs=bad error=bad-fcs "
            "fcs_received=1234 fcs_computed=beef");
}

TEST(TextOutput, BrokenFrameLine) {
  TelegramRow row;
  row.t_ps = 0;
  row.address = 9;
  row.data = {0x10};
  row.error = ErrorClass::Misaligned;
  EXPECT_EQ(text_row(row), "         0.0  -          9     1  data=10 error=misaligned");
}

TEST(TextOutput, HeaderAndSummary) {
  EXPECT_EQ(text_header(info()),
            "# sercon decode x.bits: bits, 4 Mbit/s (from --rate)\n"
            "#       t_ns  kind    addr   len  fields\n");
  DecodeSummary s;
  s.add(mst(0));
  s.add(mst(1));
  TelegramRow at = mst(1);
  at.kind = TelegramKind::AtOrMdt;
  at.phase.reset();
  s.add(at);
  EXPECT_EQ(text_summary(s, info()),
            "summary\n"
            "  telegrams  3 (MST 2, AT/MDT 1)\n"
            "  errors     0\n"
            "  phases     0 -> 1\n"
            "  bit rate   4 Mbit/s (from --rate)\n"
            "  line bits  4000\n"
            "  legend     AT/MDT = addressed telegram in CP1/CP2: the line alone cannot tell a "
            "drive's AT from the master's single-drive MDT (sercos-facts §2)\n");
}

TEST(TextOutput, LongPhaseHistoryShowsStartAndEnd) {
  DecodeSummary s;
  for (int i = 0; i < 30; ++i) s.add(mst(static_cast<unsigned>(i % 2)));
  const std::string text = text_summary(s, info());
  EXPECT_NE(text.find("  phases     0 -> 1 -> 0 -> 1 -> 0 -> 1 -> 0 -> 1 -> 0 -> 1 -> 0 -> 1 -> 0 "
                      "-> 1 -> 0 -> 1 -> ... (30 phases in all) -> 0 -> 1 -> 0 -> 1 -> 0 -> 1 -> "
                      "0 -> 1\n"),
            std::string::npos)
      << text;
}

TEST(JsonOutput, TelegramObject) {
  EXPECT_EQ(json_row(mst(4)).dump(),
            R"({"t_ns":1234.5,"kind":"MST","address":255,"length":1,"data":"04","fcs_ok":true,)"
            R"("phase":4,"phase_valid":true,"start_bit":10,"end_bit":60})");
  TelegramRow whole = mst(0);
  whole.t_ps = 8'000'000;
  EXPECT_EQ(json_row(whole)["t_ns"], 8000);  // whole nanoseconds are integers
}

TEST(JsonOutput, ErrorObjects) {
  TelegramRow row;
  row.t_ps = 500'000;
  row.address = 2;
  row.data = {0xAB};
  row.error = ErrorClass::Truncated;
  EXPECT_EQ(json_row(row).dump(),
            R"({"t_ns":500,"error":"truncated","address":2,"length":1,"data":"ab",)"
            R"("start_bit":0,"end_bit":0})");
}

TEST(JsonOutput, SummaryObject) {
  DecodeSummary s;
  s.add(mst(3));
  TelegramRow bad;
  bad.error = ErrorClass::BadFcs;
  s.add(bad);
  const auto j = json_summary(s, info());
  EXPECT_EQ(j.at("summary").at("telegrams"), 1);
  EXPECT_EQ(j.at("summary").at("fcs_errors"), 1);
  EXPECT_EQ(j.at("summary").at("phases"), nlohmann::ordered_json({3}));
  EXPECT_EQ(j.at("summary").at("bit_rate"), 4'000'000);
  EXPECT_EQ(j.at("summary").at("rate_source"), "option");
  EXPECT_EQ(j.at("summary").at("kinds").at("MST"), 1);
  EXPECT_EQ(j.at("summary").at("errors").at("bad_fcs"), 1);
}

}  // namespace
}  // namespace sercon::tools

// Requirement: a real VCD parser (issue "capture readers", VCD): header commands, scopes,
// 1-bit and wider signals, value changes 0/1/x/z/b/r, time stamps in any timescale, edges
// in picoseconds, and a clear error (never a crash) for malformed input.
#include "sercon/capture/vcd_reader.hpp"

#include <gtest/gtest.h>

#include <sstream>

#include "sercon/capture/capture_error.hpp"
#include "test_files.hpp"

namespace sercon::capture {
namespace {

VcdTrace read(const std::string& text, std::string_view signal = "") {
  std::istringstream in(text);
  return read_vcd(in, signal, "t.vcd");
}

std::string error_of(const std::string& text, std::string_view signal = "") {
  try {
    read(text, signal);
  } catch (const CaptureError& e) {
    return e.what();
  }
  return "(no error)";
}

const std::string kHeader =
    "$timescale 1 ns $end\n$scope module top $end\n$var wire 1 ! rx $end\n$upscope $end\n"
    "$enddefinitions $end\n";

struct E {
  std::int64_t t;
  bool level;
};

void expect_edges(const VcdTrace& trace, const std::vector<E>& expected) {
  ASSERT_EQ(trace.edges.size(), expected.size());
  for (std::size_t i = 0; i < expected.size(); ++i) {
    EXPECT_EQ(trace.edges[i].time_ps, expected[i].t) << i;
    EXPECT_EQ(trace.edges[i].level, expected[i].level) << i;
  }
}

TEST(VcdReader, EdgesInPicosecondsAfterTheInitialLevel) {
  const VcdTrace trace = read(kHeader + "#0\n$dumpvars\n1!\n$end\n#250\n0!\n#500 1!\n#1000\n");
  EXPECT_EQ(trace.variable.full_name(), "top.rx");
  EXPECT_EQ(trace.timescale_ps, 1000);
  EXPECT_TRUE(trace.initial_level);
  expect_edges(trace, {{250'000, false}, {500'000, true}});
  EXPECT_EQ(trace.start_ps, 0);
  EXPECT_EQ(trace.end_ps, 1'000'000);
}

// IEEE 1364 §18.2.1: an identifier code is any printable ASCII characters, '$' included
// (sigrok-cli and Icarus Verilog give the 4th signal "$"); only a command keyword inside
// $var is a missing $end.
TEST(VcdReader, AnIdentifierCodeMayBeADollarSign) {
  const std::string header =
      "$timescale 1 ns $end\n$scope module top $end\n$var wire 1 ! a $end\n"
      "$var wire 1 $ rx $end\n$var wire 1 $x b $end\n$upscope $end\n$enddefinitions $end\n";
  const VcdTrace trace = read(header + "#0 0! 1$ 0$x\n#250 0$ 1!\n#500 1$\n#600\n", "rx");
  EXPECT_EQ(trace.variable.id, "$");
  EXPECT_TRUE(trace.initial_level);
  expect_edges(trace, {{250'000, false}, {500'000, true}});
  EXPECT_NE(error_of("$timescale 1 ns $end\n$var wire 1 ! rx $scope\n"), "(no error)");
  EXPECT_NE(error_of("$timescale 1 ns $end\n$var wire 1 ! rx $scope\n").find("missing $end"),
            std::string::npos);
}

TEST(VcdReader, CaptureStartIsTheFirstTimeStamp) {
  const VcdTrace trace = read(kHeader + "#100\n0!\n#150\n1!\n#200\n");
  EXPECT_EQ(trace.start_ps, 100'000);
  EXPECT_FALSE(trace.initial_level);
  expect_edges(trace, {{150'000, true}});
}

TEST(VcdReader, RepeatedLevelsAreNoEdges) {
  const VcdTrace trace = read(kHeader + "#0 0!\n#1 0!\n#2 1!\n#3 1!\n#4 0!\n");
  expect_edges(trace, {{2000, true}, {4000, false}});
}

TEST(VcdReader, AChangeAndItsUndoAtOneInstantCancel) {
  // At #7 the level goes 1 -> 0 -> 1 in zero time: it never showed on the line.
  const VcdTrace trace = read(kHeader + "#0 0!\n#5 1!\n#7 0!\n1!\n#9 0!\n");
  expect_edges(trace, {{5000, true}, {9000, false}});
}

TEST(VcdReader, SeveralValuesAtTheFirstInstantLeaveTheLast) {
  const VcdTrace trace = read(kHeader + "#0 x!\n0!\n1!\n#3 0!\n");
  EXPECT_TRUE(trace.initial_level);
  expect_edges(trace, {{3000, false}});
}

TEST(VcdReader, XAndZKeepTheLastLevelAndAreCounted) {
  const VcdTrace trace = read(kHeader + "#0 x!\n#1 1!\n#2 z!\n#3 X!\n#4 0!\n#5 Z!\n#6 1!\n");
  EXPECT_TRUE(trace.initial_level);
  expect_edges(trace, {{4000, false}, {6000, true}});
  EXPECT_EQ(trace.unknown_values, 4U);
}

TEST(VcdReader, EveryTimescaleUnitGivesPicoseconds) {
  const std::vector<std::pair<std::string, std::int64_t>> cases{{"1 s", 1'000'000'000'000},
                                                                {"10 ms", 10'000'000'000},
                                                                {"100 us", 100'000'000},
                                                                {"1 ns", 1'000},
                                                                {"10 ps", 10},
                                                                {"1ps", 1}};
  for (const auto& [scale, ps] : cases) {
    const VcdTrace trace =
        read("$timescale " + scale + " $end\n$var wire 1 ! rx $end\n$enddefinitions $end\n" +
             "#0 0!\n#3 1!\n");
    expect_edges(trace, {{3 * ps, true}});
  }
}

TEST(VcdReader, FemtosecondTimescaleIsRejectedWithItsLine) {
  const std::string message =
      error_of("$date x $end\n$timescale 100 fs $end\n$var wire 1 ! rx $end\n");
  EXPECT_NE(message.find("t.vcd:2:"), std::string::npos) << message;
  EXPECT_NE(message.find("finer than 1 ps"), std::string::npos) << message;
}

TEST(VcdReader, NestedScopesAndSelectionByFullName) {
  const std::string text =
      "$timescale 1ns $end\n"
      "$scope module top $end\n"
      "$scope module master $end $var wire 1 ! rx $end $upscope $end\n"
      "$scope module drive1 $end $var reg 1 \" rx $end $upscope $end\n"
      "$var wire 8 # bus [7:0] $end\n"
      "$upscope $end\n$enddefinitions $end\n"
      "#0 0! 1\" b10100101 #\n#10 1! 0\" b0 #\n#20 0! 1\"\n";
  const VcdTrace master = read(text, "top.master.rx");
  expect_edges(master, {{10'000, true}, {20'000, false}});
  const VcdTrace drive = read(text, "top.drive1.rx");
  EXPECT_TRUE(drive.initial_level);
  expect_edges(drive, {{10'000, false}, {20'000, true}});
  EXPECT_NE(error_of(text, "rx").find("several signals are named 'rx'"), std::string::npos);
  EXPECT_NE(error_of(text).find("several 1-bit signals"), std::string::npos);
}

TEST(VcdReader, WideValuesAndRealsOfOtherSignalsAreSkipped) {
  const std::string text =
      "$timescale 1 us $end\n$var wire 16 % word $end\n$var real 64 & volts $end\n"
      "$var wire 1 ! rx $end\n$enddefinitions $end\n"
      "#0 b0000111100001111 % r3.3 & 0!\n#1 B1x %\nR0.5 & 1!\n#2 0!\n";
  const VcdTrace trace = read(text);
  expect_edges(trace, {{1'000'000, true}, {2'000'000, false}});
}

TEST(VcdReader, AOneBitVectorValueSetsTheLevel) {
  const VcdTrace trace = read(kHeader + "#0 b0 !\n#1 b1 !\n#2 b0 !\n");
  expect_edges(trace, {{1000, true}, {2000, false}});
}

TEST(VcdReader, MultiCharacterIdentifierCodes) {
  const std::string text =
      "$timescale 1ns $end\n$var wire 1 a{ rx $end\n$var wire 1 a tx $end\n"
      "$enddefinitions $end\n#0 0a{ 1a\n#4 1a{\n#5 0a\n";
  const VcdTrace trace = read(text, "rx");
  expect_edges(trace, {{4000, true}});
}

TEST(VcdReader, CommentsAndUnknownHeaderCommandsAreSkipped) {
  const std::string text =
      "$comment anything $var at all $end\n$version GTKWave $end\n$attrbegin misc 07 $end\n" +
      kHeader + "$comment in the body $end\n#0 0!\n$dumpall 0! $end\n#1 1!\n";
  expect_edges(read(text), {{1000, true}});
}

TEST(VcdReader, StrayTextBeforeTheHeaderIsTolerated) {
  // sigrok-cli 0.7.2 writes "META samplerate: N" before $date.
  const VcdTrace trace = read("META samplerate: 40000000\n" + kHeader + "#0 0!\n#1 1!\n");
  expect_edges(trace, {{1000, true}});
}

TEST(VcdReader, ManyChangesStreamThrough) {
  std::string text = kHeader;
  for (int i = 0; i < 200'000; ++i) {
    // Appended piece by piece: GCC 12 -O3 warns falsely (-Wrestrict) on "#" + to_string().
    text += '#';
    text += std::to_string(i);
    text += i % 2 ? " 1!\n" : " 0!\n";
  }
  const VcdTrace trace = read(text);
  EXPECT_EQ(trace.edges.size(), 199'999U);
  EXPECT_EQ(trace.edges.back().time_ps, 199'999'000);
}

TEST(VcdReader, ErrorsNameTheProblemAndTheLine) {
  struct Case {
    std::string text;
    std::string expected;
  };
  const std::vector<Case> cases{
      {"", "the file is empty"},
      {"hello world, this is not VCD at all and has no command in it anywhere here okay",
       "not a VCD file"},
      {"$timescale 1 ns $end\n$var wire 1 ! rx $end\n", "no $enddefinitions"},
      {"$var wire 1 ! rx $end\n$enddefinitions $end\n", "no $timescale"},
      {"$timescale 1 ns $end\n$enddefinitions $end\n", "no $var"},
      {"$timescale 1 ns $end\n$var wire 1 ! rx\n$enddefinitions $end\n", "missing $end"},
      {"$comment never closed\n", "no $end"},
      {"$timescale 1 ns $end\n$upscope $end\n", "$upscope without an open $scope"},
      {"$timescale 1 ns $end\n$var wire ! rx $end\n", "$var needs"},
      {"$timescale 1 ns $end\n$var wire x ! rx $end\n", "bad $var width"},
      {"$timescale 1 ns $end\n$var wire 0 ! rx $end\n", "bad $var width"},
      {"$timescale 1 ns $end\n$scope module top $end\nrx\n", "unexpected 'rx' in the VCD header"},
      {kHeader + "#0 0!\n#1 1?\n", "t.vcd:7: unknown identifier code '?'"},
      {kHeader + "#10 0!\n#5 1!\n", "time goes backwards: #5 comes after #10"},
      {kHeader + "#1x 0!\n", "bad time stamp '#1x'"},
      {kHeader + "# 0!\n", "time stamp '#' without a number"},
      {kHeader + "#99999999999999999999 0!\n", "too large"},
      {kHeader + "#0 1\n", "without an identifier code"},
      {kHeader + "#0 b012 !\n", "bad vector value"},
      {kHeader + "#0 b1\n", "the file ends after value 'b1'"},
      {kHeader + "#0 0! $end\n", "$end without an open command"},
      {kHeader + "#0 0! $var\n", "unexpected '$var' after $enddefinitions"},
      {kHeader + "#0 0! q!\n", "unexpected 'q!'"},
      {kHeader + "#0 1!\n#5\n", "has no edges: it stays high"},
      {kHeader + "#0 x!\n#5 z!\n", "never has a known level (only x/z values)"},
      {kHeader + "#0\n", "never has a known level (no values at all)"},
      {std::string("$timescale 1 ns $end\0junk", 25), "binary data"},
  };
  for (const Case& c : cases) {
    const std::string message = error_of(c.text);
    EXPECT_NE(message.find(c.expected), std::string::npos) << "input:\n"
                                                           << c.text << "\nmessage: " << message;
    EXPECT_EQ(message.rfind("t.vcd:", 0), 0U) << message;
  }
}

TEST(VcdReader, HugeTimestampsOverflowCleanlyAtCoarseTimescales) {
  const std::string text =
      "$timescale 100 s $end\n$var wire 1 ! rx $end\n$enddefinitions $end\n#0 0!\n#92233 1!\n"
      "#92234 0!\n";
  EXPECT_NE(error_of(text).find("too large"), std::string::npos) << error_of(text);
}

TEST(VcdReader, FileErrorsNameThePath) {
  testing::TempDir dir;
  try {
    read_vcd_file(dir / "missing.vcd", "");
    FAIL();
  } catch (const CaptureError& e) {
    EXPECT_NE(std::string(e.what()).find("missing.vcd"), std::string::npos) << e.what();
  }
  testing::write_file(dir / "ok.vcd", kHeader + "#0 0!\n#1 1!\n");
  EXPECT_EQ(read_vcd_file(dir / "ok.vcd", "rx").edges.size(), 1U);
}

}  // namespace
}  // namespace sercon::capture

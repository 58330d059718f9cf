// Requirement: bad input ends with a clear message naming the problem and a non-zero exit
// status (issue "sercon decode"): unreadable file, unknown extension, wrong format content,
// no such signal, several candidate signals, no edges, impossible rate, bits without
// --rate. A readable capture with broken telegrams exits 0 (decode_end_to_end_test.cpp).
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "run_sercon.hpp"
#include "sercon/wire/encoder.hpp"
#include "test_files.hpp"
#include "test_lines.hpp"

namespace sercon::testing {
namespace {

class DecodeBadInput : public ::testing::Test {
 protected:
  void SetUp() override {
    line_ = phase_walk_line().bits;
    write_file(dir_ / "good.bits", std::string(line_.packed().begin(), line_.packed().end()));
    write_file(dir_ / "good.vcd", vcd_for_line(line_, 250'000));
    write_sr(dir_ / "good.sr", sr_metadata("8 MHz", {"RX"}), oversample(line_, 2));
  }

  // Runs decode, expects failure with a message containing every piece of `expected`.
  void expect_failure(const std::vector<std::string>& args,
                      const std::vector<std::string>& expected) {
    std::vector<std::string> full{"decode"};
    full.insert(full.end(), args.begin(), args.end());
    const RunResult r = run_sercon(full);
    EXPECT_NE(r.status, 0) << r.out;
    EXPECT_GT(r.status, 0) << "a crash is not an error message";
    for (const std::string& piece : expected) {
      EXPECT_NE(r.err.find(piece), std::string::npos) << "expected '" << piece << "' in: " << r.err;
    }
  }

  std::string path(const char* name) const { return (dir_ / name).string(); }

  wire::LineBits line_;
  TempDir dir_;
};

TEST_F(DecodeBadInput, UnreadableFile) {
  expect_failure({"--rate", "4M", path("missing.bits")}, {"cannot read", "missing.bits"});
  expect_failure({"--rate", "4M", dir_.path().string()}, {"is a directory"});
}

TEST_F(DecodeBadInput, UnknownOrMissingExtension) {
  write_file(dir_ / "capture.txt", "x");
  expect_failure({path("capture.txt")}, {"unknown extension '.txt'", "--format"});
  write_file(dir_ / "capture", "x");
  expect_failure({path("capture")}, {"has no extension", "--format"});
}

TEST_F(DecodeBadInput, UnknownFormatOption) {
  expect_failure({"--format", "csv", path("good.bits")}, {"--format", "csv"});
}

// docs/decode.md "Exit status": a malformed command line is status 2 with one
// `sercon: error:` line; bad input (a readable command, a bad file) is status 1.
TEST_F(DecodeBadInput, MalformedCommandLineIsStatusTwo) {
  const RunResult bad_option = run_sercon({"decode", "--format", "csv", path("good.bits")});
  EXPECT_EQ(bad_option.status, 2);
  EXPECT_NE(bad_option.err.find("sercon: error:"), std::string::npos) << bad_option.err;
  EXPECT_EQ(run_sercon({}).status, 2);  // no subcommand
  EXPECT_EQ(run_sercon({"decode", "--rate", "4M", path("missing.bits")}).status, 1);
  EXPECT_EQ(run_sercon({"decode", "--help"}).status, 0);
}

// The same for a mistyped subcommand or an option before any: the line names the word
// (CLI11 alone said only "A subcommand is required"); CLI11's other messages stay.
TEST_F(DecodeBadInput, UnknownSubcommandIsNamed) {
  const std::vector<std::pair<std::vector<std::string>, std::string>> cases{
      {{"decod", path("good.bits")}, "sercon: error: unknown subcommand 'decod'"},
      {{"bogus"}, "sercon: error: unknown subcommand 'bogus'"},
      {{"--bogus"}, "sercon: error: unknown option '--bogus' and no subcommand"},
      {{}, "sercon: error: A subcommand is required"},
      {{"decode", "--bogus", path("good.bits")}, "not expected: --bogus"},
  };
  for (const auto& [args, expected] : cases) {
    const RunResult r = run_sercon(args);
    EXPECT_EQ(r.status, 2) << expected;
    EXPECT_NE(r.err.find(expected), std::string::npos) << "stderr: " << r.err;
    if (!args.empty() && args[0] != "decode") {
      EXPECT_NE(r.err.find("(subcommands: decode)"), std::string::npos) << r.err;
    }
  }
}

TEST_F(DecodeBadInput, WrongFormatContent) {
  expect_failure({"--format", "vcd", path("good.bits")}, {"good.bits", "not a VCD text file"});
  expect_failure({"--format", "sr", path("good.vcd")}, {"good.vcd", "not a zip archive"});
  expect_failure({"--format", "bits", "--rate", "4M", path("good.vcd")}, {"VCD text file"});
  expect_failure({"--format", "bits", "--rate", "4M", path("good.sr")}, {"zip archive"});
  write_zip(dir_ / "other.sr", {{"readme.txt", "hello"}});
  expect_failure({path("other.sr")}, {"not a sigrok session file"});
}

TEST_F(DecodeBadInput, NoSuchSignal) {
  expect_failure({"--signal", "tx", path("good.vcd")}, {"no signal named 'tx'", "top.rx"});
  expect_failure({"--signal", "TX", path("good.sr")}, {"no channel named 'TX'", "RX"});
  expect_failure({"--signal", "rx", "--rate", "4M", path("good.bits")},
                 {"--signal does not apply"});
}

TEST_F(DecodeBadInput, SeveralCandidateSignals) {
  std::string vcd = vcd_for_line(line_, 250'000);
  vcd.replace(vcd.find("$upscope"), 0, "$var wire 1 \" tx $end\n");
  write_file(dir_ / "two.vcd", vcd);
  expect_failure({path("two.vcd")}, {"several 1-bit signals: top.rx, top.tx", "--signal"});
  write_sr(dir_ / "two.sr", sr_metadata("8 MHz", {"RX", "TX"}), oversample(line_, 2));
  expect_failure({path("two.sr")}, {"several logic channels: RX, TX", "--signal"});
}

TEST_F(DecodeBadInput, NoOneBitSignal) {
  write_file(dir_ / "bus.vcd",
             "$timescale 1 ns $end\n$var wire 8 ! bus $end\n$enddefinitions $end\n#0 b0 !\n");
  expect_failure({path("bus.vcd")}, {"no 1-bit signal", "bus (8 bits)"});
}

TEST_F(DecodeBadInput, NoEdges) {
  write_file(dir_ / "flat.vcd",
             "$timescale 1 ns $end\n$var wire 1 ! rx $end\n$enddefinitions $end\n#0 1!\n#1000\n");
  expect_failure({path("flat.vcd")}, {"has no edges", "rx"});
  write_sr(dir_ / "flat.sr", sr_metadata("8 MHz", {"RX"}), std::string(1000, '\0'));
  expect_failure({path("flat.sr")}, {"has no edges", "RX"});
}

TEST_F(DecodeBadInput, ImpossibleRate) {
  expect_failure({"--rate", "3M", path("good.bits")},
                 {"impossible bit rate '3M'", "2M, 4M, 8M or 16M"});
  expect_failure({"--rate", "fast", path("good.vcd")}, {"impossible bit rate 'fast'"});
  // 8 MHz sampling (2 samples per 4 Mbit/s bit) cannot carry 16 Mbit/s.
  expect_failure({"--rate", "16M", path("good.sr")},
                 {"impossible bit rate 16 Mbit/s", "2 samples per bit"});
}

TEST_F(DecodeBadInput, RateThatNoSercosRateExplains) {
  // 1 Mbit/s: edges every 1 us are not within 10% of any SERCOS bit time.
  write_file(dir_ / "slow.vcd", vcd_for_line(line_, 1'000'000));
  expect_failure({path("slow.vcd")}, {"cannot recover the bit clock", "top.rx", "--rate"});
}

// Found while writing the VCD fuzz target: a VCD of 100 bytes with a 100 s timescale and
// --rate 16M asked for 16 G line bits (2 GiB, 15 s). Now a clear error, at once.
TEST_F(DecodeBadInput, VcdSpanningGigabytesOfLineBitsIsRefused) {
  write_file(dir_ / "huge.vcd",
             "$timescale 100 s $end\n$var wire 1 ! rx $end\n$enddefinitions $end\n"
             "#0\n1!\n#5\n0!\n#10\n1!\n");
  expect_failure({"--rate", "16M", path("huge.vcd")},
                 {"cannot recover the bit clock", "'rx'", "too long"});
}

TEST_F(DecodeBadInput, BitsWithoutRate) {
  expect_failure({path("good.bits")}, {"bits format carries no timing", "--rate"});
}

TEST_F(DecodeBadInput, NoFrameAtAll) {
  wire::LineEncoder idle_only;
  idle_only.idle(4000);
  const wire::LineBits bits = idle_only.take();
  write_file(dir_ / "idle.bits", std::string(bits.packed().begin(), bits.packed().end()));
  expect_failure({"--rate", "4M", path("idle.bits")}, {"no SERCOS frame found", "idle.bits"});
}

TEST_F(DecodeBadInput, MissingFileArgument) { expect_failure({}, {"FILE"}); }

// docs/decode.md "sr": the data entries are concatenated in order, and a gap is an error.
// Stopping at it decoded the part before the gap only, exit 0, as if it were all.
TEST_F(DecodeBadInput, SigrokSessionWithAMissingDataEntry) {
  const std::string samples = oversample(line_, 2);
  const std::size_t half = samples.size() / 2;
  write_zip(dir_ / "gap.sr", {{"version", "2"},
                              {"metadata", sr_metadata("8 MHz", {"RX"})},
                              {"logic-1-1", samples.substr(0, half)},
                              {"logic-1-3", samples.substr(half)}});
  expect_failure({path("gap.sr")}, {"gap.sr", "'logic-1-2' is missing", "'logic-1-3'"});
}

// docs/decode.md "Exit status": 0 only when the listing was written. Stdout on a full disk
// (/dev/full) or closed loses it: exit 1 with the reason, never 0 with nothing said.
TEST_F(DecodeBadInput, OutputThatCannotBeWritten) {
  const std::string capture = source_dir() + "/captures/phase-up-4drives.bits";
  std::vector<std::string> redirections{">&-"};
  if (std::filesystem::exists("/dev/full")) redirections.push_back(">/dev/full");
  for (const std::string& stdout_to : redirections) {
    for (const char* json : {"", " --json"}) {
      const std::string command = shell_quote(SERCON_BINARY) + " decode" + json + " --rate 4M " +
                                  shell_quote(capture) + " " + stdout_to + " 2>" +
                                  shell_quote(path("err"));
      const int status = run_command(command);
      const std::string err = read_file(dir_ / "err");
      EXPECT_EQ(status, 1) << command << "\nstderr: " << err;
      EXPECT_NE(err.find("sercon decode: error: cannot write the output: "), std::string::npos)
          << command << "\nstderr: " << err;
    }
  }
}

}  // namespace
}  // namespace sercon::testing

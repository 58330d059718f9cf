// Requirement: the sr and VCD readers handle files written by the real sigrok-cli
// (issue "capture readers": check what sigrok-cli actually writes). Skipped when
// sigrok-cli is not installed (scripts/install-deps installs it).
#include <gtest/gtest.h>

#include <algorithm>
#include <functional>
#include <sstream>

#include "sercon/capture/capture_error.hpp"
#include "sercon/capture/sr_reader.hpp"
#include "sercon/capture/vcd_reader.hpp"
#include "sercon/wire/encoder.hpp"
#include "test_files.hpp"

namespace sercon::capture {
namespace {

using testing::shell_quote;
using testing::TempDir;

class SigrokCli : public ::testing::Test {
 protected:
  void SetUp() override {
    tool_ = testing::sigrok_cli();
    if (tool_.empty()) GTEST_SKIP() << "sigrok-cli not installed";
  }

  void run(const std::string& args) {
    const std::string command = shell_quote(tool_) + " " + args + " >/dev/null 2>&1";
    ASSERT_EQ(testing::run_command(command), 0) << command;
  }

  // A short SERCOS line: fill, an MST and an AT, fill.
  static wire::LineBits line() {
    wire::LineEncoder enc;
    enc.idle(16);
    const std::uint8_t mst[] = {0x04};
    enc.telegram(255, mst);
    enc.idle(20);
    const std::uint8_t at[] = {0x00, 0xC0, 0x00, 0x00, 0x12, 0x34, 0x56, 0x78};
    enc.telegram(3, at);
    enc.idle(16);
    return enc.take();
  }

  std::string tool_;
  TempDir dir_;
};

TEST_F(SigrokCli, DemoDeviceSessionReadsAsD0) {
  const auto file = dir_ / "demo.sr";
  run("-d demo --channels D0 --samples 1000 -o " + shell_quote(file.string()));
  const SrChannel channel = read_sr_file(file, "");
  EXPECT_EQ(channel.name, "D0");
  EXPECT_EQ(channel.sample_count, 1000U);
  EXPECT_EQ(channel.samplerate_hz, 200'000U);
  EXPECT_EQ(channel.sample_period_ps, 5'000'000);
}

// Which bit holds which probe is what sigrok-cli itself reads back (its CSV output), for
// a session with a gap in the probe numbers (D0, D1, D3 = probe1, probe2, probe4).
TEST_F(SigrokCli, ChannelsAgreeWithSigrokClisOwnReading) {
  const auto file = dir_ / "demo3.sr";
  const auto csv = dir_ / "demo3.csv";
  run("-d demo --channels D0,D1,D3 --samples 3000 -o " + shell_quote(file.string()));
  run("-i " + shell_quote(file.string()) + " -O csv -o " + shell_quote(csv.string()));
  EXPECT_THROW(read_sr_file(file, ""), CaptureError);  // three channels: --signal needed

  std::vector<std::string> rows;  // "1,0,1" per sample
  std::istringstream lines(testing::read_file(csv));
  for (std::string line; std::getline(lines, line);) {
    if (!line.empty() && line[0] != ';' && line.rfind("logic", 0) != 0) rows.push_back(line);
  }
  ASSERT_EQ(rows.size(), 3000U);
  const std::vector<std::string> names{"D0", "D1", "D3"};
  for (std::size_t column = 0; column < names.size(); ++column) {
    std::vector<bool> expected;
    for (const std::string& row : rows) expected.push_back(row.at(2 * column) == '1');
    const bool constant = std::adjacent_find(expected.begin(), expected.end(),
                                             std::not_equal_to<>()) == expected.end();
    if (constant) {  // sigrok sees no edges there; neither may we
      EXPECT_THROW(read_sr_file(file, names[column]), CaptureError) << names[column];
      continue;
    }
    const SrChannel channel = read_sr_file(file, names[column]);
    ASSERT_EQ(channel.sample_count, expected.size());
    for (std::size_t k = 0; k < expected.size(); ++k) {
      ASSERT_EQ(((channel.samples[k / 64] >> (k % 64)) & 1U) != 0, expected[k])
          << names[column] << " sample " << k;
    }
  }
}

TEST_F(SigrokCli, BinaryInputToSessionKeepsEverySample) {
  const wire::LineBits bits = line();
  const std::string samples = testing::oversample(bits, 8);
  testing::write_file(dir_ / "in.bin", samples);
  const auto file = dir_ / "line.sr";
  run("-I binary:numchannels=1:samplerate=64000000 -i " + shell_quote((dir_ / "in.bin").string()) +
      " -o " + shell_quote(file.string()));
  const SrChannel channel = read_sr_file(file, "0");  // sigrok names the channel "0"
  EXPECT_EQ(channel.sample_period_ps, 15'625);
  ASSERT_EQ(channel.sample_count, samples.size());
  for (std::size_t k = 0; k < samples.size(); ++k) {
    ASSERT_EQ(((channel.samples[k / 64] >> (k % 64)) & 1U) != 0, samples[k] == 1) << k;
  }
}

TEST_F(SigrokCli, BinaryInputToVcdGivesTheEdgesWithinItsRounding) {
  const wire::LineBits bits = line();
  testing::write_file(dir_ / "in.bin", testing::oversample(bits, 8));
  const auto file = dir_ / "line.vcd";
  run("-I binary:numchannels=1:samplerate=64000000 -i " + shell_quote((dir_ / "in.bin").string()) +
      " -O vcd -o " + shell_quote(file.string()));
  const VcdTrace trace = read_vcd_file(file, "");
  EXPECT_EQ(trace.variable.reference, "0");
  EXPECT_EQ(trace.initial_level, bits[0]);
  // 8 samples of 15.625 ns per 125 ns bit; sigrok writes 100 ps units, rounded.
  std::vector<std::int64_t> expected;
  for (std::size_t i = 1; i < bits.size(); ++i) {
    if (bits[i] != bits[i - 1]) expected.push_back(static_cast<std::int64_t>(i) * 125'000);
  }
  ASSERT_EQ(trace.edges.size(), expected.size());
  for (std::size_t i = 0; i < expected.size(); ++i) {
    EXPECT_NEAR(static_cast<double>(trace.edges[i].time_ps), static_cast<double>(expected[i]),
                100.0)
        << "edge " << i;
  }
}

// sigrok-cli numbers VCD identifier codes from '!', so the 4th channel's is '$' (VCD allows
// any printable character); reading channel 3 of an 8-channel capture must work.
TEST_F(SigrokCli, EightChannelVcdReadsTheChannelWhoseIdentifierIsDollar) {
  const wire::LineBits bits = line();
  std::string samples = testing::oversample(bits, 8);
  for (char& c : samples) c = static_cast<char>(c << 3);  // the line on channel 3
  testing::write_file(dir_ / "in.bin", samples);
  const auto file = dir_ / "eight.vcd";
  run("-I binary:numchannels=8:samplerate=64000000 -i " + shell_quote((dir_ / "in.bin").string()) +
      " -O vcd -o " + shell_quote(file.string()));
  const VcdTrace trace = read_vcd_file(file, "3");
  EXPECT_EQ(trace.variable.reference, "3");
  EXPECT_EQ(trace.variable.id, "$");
  EXPECT_EQ(trace.initial_level, bits[0]);
  std::size_t changes = 0;
  for (std::size_t i = 1; i < bits.size(); ++i)
    if (bits[i] != bits[i - 1]) ++changes;
  EXPECT_EQ(trace.edges.size(), changes);
}

}  // namespace
}  // namespace sercon::capture

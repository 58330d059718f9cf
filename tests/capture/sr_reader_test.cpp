// Requirement: sigrok session files (.sr, zip, format version 2; version 1 single entry)
// read as the packed 1-bit samples of one logic channel (issue "capture readers", sr).
// The zips here are built with libzip; sigrok_cli_test.cpp reads files sigrok-cli wrote.
#include "sercon/capture/sr_reader.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <optional>
#include <string>

#include "sercon/capture/capture_error.hpp"
#include "test_files.hpp"

namespace sercon::capture {
namespace {

using testing::TempDir;

bool sample(const SrChannel& channel, std::size_t k) {
  return ((channel.samples[k / 64] >> (k % 64)) & 1U) != 0;
}

std::string error_of(const std::filesystem::path& file, std::string_view signal = "") {
  try {
    read_sr_file(file, signal);
  } catch (const CaptureError& e) {
    return e.what();
  }
  return "(no error)";
}

// Levels 0,1,1,0,0,0,1,... with a 3-sample period pattern, as one byte per sample.
std::string pattern_samples(std::size_t count, unsigned unitsize, unsigned bit) {
  std::string out;
  for (std::size_t k = 0; k < count; ++k) {
    std::string s(unitsize, '\x00');
    // Other channels toggle too, so a wrong bit selection shows.
    for (auto& c : s) c = static_cast<char>(k % 2 ? 0xFF : 0x00);
    const bool high = (k * 7 / 3) % 2 == 1;
    auto& byte = s[bit / 8];
    const auto mask = static_cast<unsigned char>(1U << (bit % 8));
    byte = static_cast<char>(high ? (static_cast<unsigned char>(byte) | mask)
                                  : (static_cast<unsigned char>(byte) & ~mask));
    out += s;
  }
  return out;
}

void expect_pattern(const SrChannel& channel, std::size_t count) {
  ASSERT_EQ(channel.sample_count, count);
  ASSERT_EQ(channel.samples.size(), (count + 63) / 64);
  for (std::size_t k = 0; k < count; ++k) {
    ASSERT_EQ(sample(channel, k), (k * 7 / 3) % 2 == 1) << "sample " << k;
  }
}

TEST(SrReader, OneChannelVersion2) {
  TempDir dir;
  testing::write_sr(dir / "a.sr", testing::sr_metadata("64 MHz", {"D0"}),
                    pattern_samples(1000, 1, 0), 256);
  const SrChannel channel = read_sr_file(dir / "a.sr", "");
  EXPECT_EQ(channel.name, "D0");
  EXPECT_EQ(channel.samplerate_hz, 64'000'000U);
  EXPECT_EQ(channel.sample_period_ps, 15'625);
  expect_pattern(channel, 1000);
}

TEST(SrReader, ChannelByNameInTwoByteSamplesSplitAcrossOddChunks) {
  TempDir dir;
  std::vector<std::string> probes;
  for (int i = 0; i < 16; ++i) probes.push_back(std::string("D").append(std::to_string(i)));
  // 777-byte chunks cut samples in half: the reader must carry the split sample over.
  testing::write_sr(dir / "b.sr", testing::sr_metadata("1 MHz", probes, 2),
                    pattern_samples(5000, 2, 9), 777);
  const SrChannel channel = read_sr_file(dir / "b.sr", "D9");
  EXPECT_EQ(channel.name, "D9");
  EXPECT_EQ(channel.sample_period_ps, 1'000'000);
  expect_pattern(channel, 5000);
}

TEST(SrReader, Version1SingleEntry) {
  TempDir dir;
  testing::write_zip(dir / "v1.sr", {{"version", "1"},
                                     {"metadata", testing::sr_metadata("24 MHz", {"rx"})},
                                     {"logic-1", pattern_samples(300, 1, 0)}});
  const SrChannel channel = read_sr_file(dir / "v1.sr", "rx");
  EXPECT_EQ(channel.sample_period_ps, 41'667);  // 41666.67 ps rounded
  expect_pattern(channel, 300);
}

TEST(SrReader, ChannelSelectionErrorsListTheChannels) {
  TempDir dir;
  testing::write_sr(dir / "c.sr", testing::sr_metadata("1 MHz", {"RX", "TX"}),
                    pattern_samples(100, 1, 0));
  std::string message = error_of(dir / "c.sr");
  EXPECT_NE(message.find("several logic channels: RX, TX"), std::string::npos) << message;
  EXPECT_NE(message.find("--signal"), std::string::npos) << message;
  message = error_of(dir / "c.sr", "CLK");
  EXPECT_NE(message.find("no channel named 'CLK'"), std::string::npos) << message;
  EXPECT_NE(message.find("(channels: RX, TX)"), std::string::npos) << message;
  EXPECT_NO_THROW(read_sr_file(dir / "c.sr", "RX"));
}

TEST(SrReader, AConstantChannelHasNoEdges) {
  TempDir dir;
  testing::write_sr(dir / "flat.sr", testing::sr_metadata("1 MHz", {"D0"}),
                    std::string(500, '\x01'));
  const std::string message = error_of(dir / "flat.sr");
  EXPECT_NE(message.find("has no edges: it stays high for all 500 samples"), std::string::npos)
      << message;
}

TEST(SrReader, BrokenFilesAreNamed) {
  TempDir dir;
  const std::string meta = testing::sr_metadata("1 MHz", {"D0"});
  struct Case {
    std::string name;
    std::vector<std::pair<std::string, std::string>> entries;  // empty: not a zip
    std::string expected;
  };
  const std::vector<Case> cases{
      {"no-version.sr", {{"metadata", meta}, {"logic-1-1", "\x01"}}, "no 'version' entry"},
      {"no-metadata.sr", {{"version", "2"}, {"logic-1-1", "\x01"}}, "no 'metadata' entry"},
      {"version3.sr", {{"version", "3"}, {"metadata", meta}}, "version '3' is not supported"},
      {"no-data.sr", {{"version", "2"}, {"metadata", meta}}, "no logic data"},
      {"bad-meta.sr",
       {{"version", "2"}, {"metadata", "[device 1]\ncapturefile=logic-1\n"}},
       "no 'samplerate'"},
      {"empty-data.sr", {{"version", "2"}, {"metadata", meta}, {"logic-1-1", ""}}, "no samples"},
      {"truncated.sr",
       {{"version", "2"},
        {"metadata", testing::sr_metadata("1 MHz", {"D0"}, 2)},
        {"logic-1-1", std::string("\x01\x00\x01", 3)}},
       "ends inside a sample"},
      // docs/decode.md "sr": a gap in the numbered entries is an error, not the data's end.
      {"gap.sr",
       {{"version", "2"},
        {"metadata", meta},
        {"logic-1-1", "\x01\x00"},
        {"logic-1-4", "\x01"},
        {"logic-1-3", "\x01"}},
       "'logic-1-2' is missing but 'logic-1-3' is there"},
      {"no-first.sr",
       {{"version", "2"}, {"metadata", meta}, {"logic-1", "\x01\x00"}, {"logic-1-2", "\x01"}},
       "'logic-1-1' is missing but 'logic-1-2' is there"},
  };
  for (const Case& c : cases) {
    testing::write_zip(dir / c.name, c.entries);
    const std::string message = error_of(dir / c.name);
    EXPECT_NE(message.find(c.expected), std::string::npos) << c.name << ": " << message;
    EXPECT_NE(message.find(c.name), std::string::npos) << c.name << ": " << message;
  }
}

// Brief (fuzzing: cap sizes): the samples read from one session are capped (kMaxSrSamples,
// 2^33), since deflated data can expand a thousandfold; past the cap a clear error, and
// nothing more is read. Checked here with a small cap.
TEST(SrReader, MoreSamplesThanTheCapIsAClearError) {
  TempDir dir;
  testing::write_sr(dir / "long.sr", testing::sr_metadata("1 MHz", {"D0"}),
                    pattern_samples(5000, 1, 0), 777);
  EXPECT_EQ(read_sr_file(dir / "long.sr", "", 5000).sample_count, 5000U);
  try {
    read_sr_file(dir / "long.sr", "", 4999);
    FAIL() << "no error";
  } catch (const CaptureError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("long.sr: the logic data holds more than 4999 samples"),
              std::string::npos)
        << message;
  }
  EXPECT_EQ(kMaxSrSamples, std::uint64_t{1} << 33);
}

// Makes the local and central headers of `entry` claim `uncompressed` bytes, and
// `compressed` bytes too when given (zip format: local header PK\3\4 with the sizes at
// +18/+22 and the name at +30; central header PK\1\2, sizes at +20/+24, name at +46).
void claim_sizes(std::string& zip, const std::string& entry,
                 std::optional<std::uint32_t> compressed, std::uint32_t uncompressed) {
  const auto put = [&](std::size_t at, std::uint32_t v) {
    for (std::size_t i = 0; i < 4; ++i) zip[at + i] = static_cast<char>((v >> (8 * i)) & 0xFF);
  };
  const auto u16 = [&](std::size_t at) {
    return static_cast<std::size_t>(static_cast<unsigned char>(zip[at])) |
           static_cast<std::size_t>(static_cast<unsigned char>(zip[at + 1])) << 8;
  };
  struct Header {
    std::string signature;
    std::size_t sizes, name_length, name;
  };
  for (const Header& h : {Header{"PK\3\4", 18, 26, 30}, Header{"PK\1\2", 20, 28, 46}}) {
    for (std::size_t at = zip.find(h.signature); at != std::string::npos;
         at = zip.find(h.signature, at + 4)) {
      if (zip.compare(at + h.name, u16(at + h.name_length), entry) != 0) continue;
      if (compressed) put(at + h.sizes, *compressed);
      put(at + h.sizes + 4, uncompressed);
    }
  }
}

// Brief (fuzzing: a zip claiming a huge logic chunk): the reader streams entries in 64 KiB
// blocks and sizes nothing by what the zip claims. An entry claiming 4 GiB, stored or
// deflated, its uncompressed size or both sizes, gives either a clear error naming it or
// its real data; never an allocation of gigabytes.
TEST(SrReader, AZipClaimingAHugeLogicEntryGivesAnErrorOrItsRealData) {
  TempDir dir;
  const std::string meta = testing::sr_metadata("1 MHz", {"D0"});
  for (bool stored : {true, false}) {
    for (bool both : {false, true}) {
      SCOPED_TRACE(std::string(stored ? "stored" : "deflated") + (both ? ", both sizes" : ""));
      testing::write_zip(
          dir / "claim.sr",
          {{"version", "2"}, {"metadata", meta}, {"logic-1-1", pattern_samples(20000, 1, 0)}},
          stored);
      std::string zip = testing::read_file(dir / "claim.sr");
      const std::uint32_t huge = 0xFFFFFFF0;
      claim_sizes(zip, "logic-1-1", both ? std::optional<std::uint32_t>(huge) : std::nullopt, huge);
      testing::write_file(dir / "claim.sr", zip);
      try {
        expect_pattern(read_sr_file(dir / "claim.sr", ""), 20000);
      } catch (const CaptureError& e) {
        EXPECT_NE(std::string(e.what()).find("entry 'logic-1-1'"), std::string::npos) << e.what();
      }
    }
  }
}

TEST(SrReader, NotAZipOrNotThere) {
  TempDir dir;
  testing::write_file(dir / "text.sr", "$timescale 1 ns $end\n");
  EXPECT_NE(error_of(dir / "text.sr").find("not a sigrok session file (not a zip archive)"),
            std::string::npos)
      << error_of(dir / "text.sr");
  EXPECT_NE(error_of(dir / "gone.sr").find("cannot read"), std::string::npos);
  EXPECT_NE(error_of(dir.path()).find("is a directory"), std::string::npos);
}

}  // namespace
}  // namespace sercon::capture

// Requirement: the bits format is the line levels packed MSB first, 8 x file size bits
// (issue "capture readers", bits); other formats fed to it are named, not decoded as noise.
#include "sercon/capture/bits_file.hpp"

#include <gtest/gtest.h>

#include "sercon/capture/capture_error.hpp"
#include "test_files.hpp"

namespace sercon::capture {
namespace {

using testing::TempDir;

std::string error_of(const std::filesystem::path& file) {
  try {
    read_bits_file(file);
  } catch (const CaptureError& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(BitsFile, EveryBitMsbFirst) {
  TempDir dir;
  testing::write_file(dir / "a.bits", std::string("\xA0\x01", 2));
  const wire::LineBits bits = read_bits_file(dir / "a.bits");
  ASSERT_EQ(bits.size(), 16U);
  const bool expected[16] = {1, 0, 1, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 1};
  for (std::size_t i = 0; i < 16; ++i) EXPECT_EQ(bits[i], expected[i]) << i;
}

TEST(BitsFile, WriteThenReadIsTheSameLine) {
  TempDir dir;
  wire::LineBits bits;
  for (int i = 0; i < 1000; ++i) bits.push_back((i * 13) % 7 < 3);
  write_bits_file(dir / "b.bits", bits);
  EXPECT_EQ(std::filesystem::file_size(dir / "b.bits"), 125U);
  EXPECT_EQ(read_bits_file(dir / "b.bits"), bits);
}

TEST(BitsFile, ProblemsAreNamed) {
  TempDir dir;
  EXPECT_NE(error_of(dir / "none.bits").find("cannot read"), std::string::npos);
  EXPECT_NE(error_of(dir.path()).find("is a directory"), std::string::npos);
  testing::write_file(dir / "empty.bits", "");
  EXPECT_NE(error_of(dir / "empty.bits").find("is empty"), std::string::npos);
  testing::write_file(dir / "zip.bits", std::string("PK\x03\x04rest", 8));
  EXPECT_NE(error_of(dir / "zip.bits").find("zip archive"), std::string::npos);
  testing::write_file(dir / "vcd.bits", "$date x $end\n$timescale 1 ns $end\n");
  EXPECT_NE(error_of(dir / "vcd.bits").find("VCD text file"), std::string::npos);
}

}  // namespace
}  // namespace sercon::capture

// FCS: CRC-16/X.25 as sercos-facts §1 defines it, checked against its test vectors.
#include "sercon/wire/fcs.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <vector>

namespace sercon::wire {
namespace {

std::uint16_t fcs_of(std::vector<std::uint8_t> bytes) { return fcs16(bytes); }

// sercos-facts §1: FCS test vector FF 00 87 F0 (MST, CP0); low byte 0x87 goes first.
TEST(Fcs, VectorMstCp0) { EXPECT_EQ(fcs_of({0xFF, 0x00}), 0xF087); }

// sercos-facts §1: FCS test vector FF 01 0E E1 (MST, CP1).
TEST(Fcs, VectorMstCp1) { EXPECT_EQ(fcs_of({0xFF, 0x01}), 0xE10E); }

// sercos-facts §1: FCS test vector FF 02 95 D3 (MST, CP2).
TEST(Fcs, VectorMstCp2) { EXPECT_EQ(fcs_of({0xFF, 0x02}), 0xD395); }

// sercos-facts §1: CRC-16/X.25 — the standard check value of "123456789" is 0x906E,
// which pins polynomial 0x8408, init 0xFFFF and final XOR 0xFFFF together.
TEST(Fcs, StandardCheckValue) {
  const std::vector<std::uint8_t> digits = {'1', '2', '3', '4', '5', '6', '7', '8', '9'};
  EXPECT_EQ(fcs16(digits), 0x906E);
}

// sercos-facts §1: FCS over address + data; the incremental form agrees with one shot at
// every split point.
// Every span length through the table paths (8, 4 and 1 byte at a time) against the CRC
// computed bit by bit from its definition.
TEST(Fcs, EveryLengthMatchesBitwiseCrc) {
  std::vector<std::uint8_t> bytes(40);
  for (std::size_t i = 0; i < bytes.size(); ++i) bytes[i] = static_cast<std::uint8_t>(i * 91 + 17);
  for (std::size_t n = 0; n <= bytes.size(); ++n) {
    unsigned crc = 0xFFFF;
    for (std::size_t i = 0; i < n; ++i) {
      crc ^= bytes[i];
      for (int bit = 0; bit < 8; ++bit) crc = (crc & 1u) ? (crc >> 1) ^ 0x8408u : crc >> 1;
    }
    EXPECT_EQ(fcs16(std::span(bytes).first(n)), crc ^ 0xFFFFu) << "length " << n;
  }
}

TEST(Fcs, IncrementalEqualsOneShot) {
  std::vector<std::uint8_t> bytes(40);
  for (std::size_t i = 0; i < bytes.size(); ++i) bytes[i] = static_cast<std::uint8_t>(i * 37 + 5);
  for (std::size_t split = 0; split <= bytes.size(); ++split) {
    Fcs16 f;
    f.update(std::span(bytes).first(split));
    for (std::size_t i = split; i < bytes.size(); ++i) f.update(bytes[i]);
    EXPECT_EQ(f.value(), fcs16(bytes)) << "split " << split;
  }
  Fcs16 f;
  f.update(0x12);
  f.reset();
  EXPECT_EQ(f.value(), fcs16({}));
}

}  // namespace
}  // namespace sercon::wire

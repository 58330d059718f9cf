// Helpers of the serial unit checked against the wire codec: telegram length without
// encoding (burst_duration), the address byte's end (start event), edge counting (line
// monitor). Facts §1: stuffing "after five consecutive 1 bits ... (applies to address, data
// and FCS, not to the flags)".
#include <gtest/gtest.h>

#include <cstdint>
#include <random>
#include <vector>

#include "sercon/chip/line_edges.hpp"
#include "sercon/chip/line_length.hpp"
#include "sercon/wire/encoder.hpp"

namespace sercon::chip {
namespace {

// burst_duration() without encoding: the same bit count as wire::LineEncoder writes.
TEST(serial_LineLength, EqualsTheEncodersOutputForRandomTelegrams) {
  std::mt19937 rng(7);
  for (int i = 0; i < 2000; ++i) {
    std::vector<std::uint8_t> data(rng() % 64);
    for (auto& byte : data) byte = static_cast<std::uint8_t>(rng() % 4 == 0 ? 0xFF : rng());
    const auto address = static_cast<std::uint8_t>(rng());
    wire::LineEncoder enc(true);
    enc.telegram(address, data);
    EXPECT_EQ(telegram_line_bits(address, data), enc.size());
  }
}

// The start event comes once the address byte is in (serial_unit.hpp): a 0 stuffed inside
// the address delays it, one stuffed after its last bit does not.
TEST(serial_LineLength, AddressEndCountsStuffingInsideTheAddressOnly) {
  EXPECT_EQ(address_end_bit(0x00), 16u);
  EXPECT_EQ(address_end_bit(0x1F), 17u);  // 1 1 1 1 1 (0) 0 0 0
  EXPECT_EQ(address_end_bit(0xF8), 16u);  // five 1s end with bit 7: the 0 comes after
  EXPECT_EQ(address_end_bit(0xFF), 17u);  // 1 1 1 1 1 (0) 1 1 1
}

// The line monitor counts a burst's edges (decision: bit 0 is an edge) word by word.
TEST(serial_LineEdges, CountAndFindMatchTheSlowWay) {
  std::mt19937 rng(11);
  for (int i = 0; i < 200; ++i) {
    wire::LineBits bits;
    const std::size_t n = 1 + rng() % 300;
    for (std::size_t k = 0; k < n; ++k) bits.push_back(rng() % 3 == 0);
    std::vector<std::size_t> edges;
    for (std::size_t k = 0; k < n; ++k) {
      const bool before = k == 0 ? !bits.level(0) : bits.level(k - 1);
      if (bits.level(k) != before) edges.push_back(k);
    }
    EXPECT_EQ(count_edges(bits, n), edges.size());
    EXPECT_EQ(count_edges(bits, n + 50), edges.size());
    const std::size_t half = n / 2;
    std::size_t below = 0;
    for (const std::size_t e : edges) below += e < half ? 1 : 0;
    EXPECT_EQ(count_edges(bits, half), below);
    for (std::size_t j = 0; j < edges.size(); ++j) EXPECT_EQ(nth_edge_bit(bits, j + 1), edges[j]);
    EXPECT_EQ(nth_edge_bit(bits, edges.size() + 1), n);
  }
}

}  // namespace
}  // namespace sercon::chip

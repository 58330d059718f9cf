// CRC-16/X.25 (sercos-facts §1), table-driven: one lookup per byte, or slicing-by-8 (eight
// independent lookups per 8 bytes) and slicing-by-4 on longer spans.
#include "sercon/wire/fcs.hpp"

#include <array>

namespace sercon::wire {
namespace {

using Table = std::array<std::array<std::uint16_t, 256>, 8>;

// t[0][x]: the register after byte x; t[k][x]: after byte x followed by k zero bytes.
constexpr Table make_tables() {
  Table t{};
  for (unsigned i = 0; i < 256; ++i) {
    unsigned crc = i;
    for (int bit = 0; bit < 8; ++bit) crc = (crc & 1u) ? (crc >> 1) ^ 0x8408u : crc >> 1;
    t[0][i] = static_cast<std::uint16_t>(crc);
  }
  for (std::size_t k = 1; k < 8; ++k)
    for (unsigned i = 0; i < 256; ++i)
      t[k][i] = static_cast<std::uint16_t>((t[k - 1][i] >> 8) ^ t[0][t[k - 1][i] & 0xFFu]);
  return t;
}

constexpr Table kTables = make_tables();
constexpr const std::array<std::uint16_t, 256>& kTable = kTables[0];

}  // namespace

const std::array<std::array<std::uint16_t, 256>, 8> kFcsTables = kTables;

void Fcs16::update(std::uint8_t byte) {
  crc_ = static_cast<std::uint16_t>((crc_ >> 8) ^ kTable[(crc_ ^ byte) & 0xFFu]);
}

void Fcs16::update(std::span<const std::uint8_t> bytes) {
  unsigned crc = crc_;
  const std::uint8_t* p = bytes.data();
  std::size_t n = bytes.size();
  // The 16-bit register only meets the first two bytes; the CRC is linear, so each byte's
  // effect through the bytes after it comes from its own table.
  for (; n >= 8; n -= 8, p += 8) {
    crc = kTables[7][(crc ^ p[0]) & 0xFFu] ^ kTables[6][((crc >> 8) ^ p[1]) & 0xFFu] ^
          kTables[5][p[2]] ^ kTables[4][p[3]] ^ kTables[3][p[4]] ^ kTables[2][p[5]] ^
          kTables[1][p[6]] ^ kTables[0][p[7]];
  }
  if (n >= 4) {  // telegrams are short: most of their bytes are in the last 7
    crc = kTables[3][(crc ^ p[0]) & 0xFFu] ^ kTables[2][((crc >> 8) ^ p[1]) & 0xFFu] ^
          kTables[1][p[2]] ^ kTables[0][p[3]];
    n -= 4;
    p += 4;
  }
  for (; n > 0; --n, ++p) crc = (crc >> 8) ^ kTable[(crc ^ *p) & 0xFFu];
  crc_ = static_cast<std::uint16_t>(crc);
}

std::uint16_t fcs16(std::span<const std::uint8_t> address_and_data) {
  Fcs16 f;
  f.update(address_and_data);
  return f.value();
}

}  // namespace sercon::wire

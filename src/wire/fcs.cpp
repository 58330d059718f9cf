// CRC-16/X.25 (sercos-facts §1), one table lookup per byte.
#include "sercon/wire/fcs.hpp"

#include <array>

namespace sercon::wire {
namespace {

constexpr std::array<std::uint16_t, 256> make_table() {
  std::array<std::uint16_t, 256> table{};
  for (unsigned i = 0; i < 256; ++i) {
    unsigned crc = i;
    for (int bit = 0; bit < 8; ++bit) crc = (crc & 1u) ? (crc >> 1) ^ 0x8408u : crc >> 1;
    table[i] = static_cast<std::uint16_t>(crc);
  }
  return table;
}

constexpr std::array<std::uint16_t, 256> kTable = make_table();

}  // namespace

void Fcs16::update(std::uint8_t byte) {
  crc_ = static_cast<std::uint16_t>((crc_ >> 8) ^ kTable[(crc_ ^ byte) & 0xFFu]);
}

void Fcs16::update(std::span<const std::uint8_t> bytes) {
  unsigned crc = crc_;
  for (std::uint8_t b : bytes) crc = (crc >> 8) ^ kTable[(crc ^ b) & 0xFFu];
  crc_ = static_cast<std::uint16_t>(crc);
}

std::uint16_t fcs16(std::span<const std::uint8_t> address_and_data) {
  Fcs16 f;
  f.update(address_and_data);
  return f.value();
}

}  // namespace sercon::wire

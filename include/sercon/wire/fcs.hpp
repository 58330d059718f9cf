// Frame check sequence of SERCOS II telegrams (sercos-facts §1): CRC-16/X.25, reflected
// polynomial 0x8408, initial value 0xFFFF, final XOR 0xFFFF, over address + data.
// The value is sent low byte first.
#pragma once

#include <array>
#include <cstdint>
#include <span>

namespace sercon::wire {

// kFcsTables[0][x]: the CRC register after byte x; [k][x]: after byte x and k zero bytes.
extern const std::array<std::array<std::uint16_t, 256>, 8> kFcsTables;

// FCS as transmitted (after the final XOR). fcs16({FF 00}) == 0xF087, sent as 87 F0.
std::uint16_t fcs16(std::span<const std::uint8_t> address_and_data);

// Incremental, table-driven form: feed bytes in line order, read value() at any time.
class Fcs16 {
 public:
  void update(std::uint8_t byte);
  void update(std::span<const std::uint8_t> bytes);
  // `n` (1..8) bytes at once, the first in the lowest bits of `bytes` (bits above them are
  // not read): slicing by 8, with n < 8 bytes taken as 8 - n zero bytes before them (a
  // table gives 0 for a 0 byte). Inline: the encoder's word loop.
  void update_word(std::uint64_t bytes, unsigned n) {
    std::uint64_t x = bytes ^ crc_;
    if (n < 4) {                              // fewer lookups byte by byte
      unsigned crc = n == 1 ? crc_ >> 8 : 0;  // the register's high byte meets the second byte
      for (unsigned i = 0; i < n; ++i) crc ^= kFcsTables[n - 1 - i][(x >> (8 * i)) & 0xFFu];
      crc_ = static_cast<std::uint16_t>(crc);
      return;
    }
    x <<= 64 - 8 * n;
    crc_ = static_cast<std::uint16_t>(
        kFcsTables[7][x & 0xFFu] ^ kFcsTables[6][(x >> 8) & 0xFFu] ^
        kFcsTables[5][(x >> 16) & 0xFFu] ^ kFcsTables[4][(x >> 24) & 0xFFu] ^
        kFcsTables[3][(x >> 32) & 0xFFu] ^ kFcsTables[2][(x >> 40) & 0xFFu] ^
        kFcsTables[1][(x >> 48) & 0xFFu] ^ kFcsTables[0][x >> 56]);
  }
  // The FCS of everything fed so far, as transmitted.
  std::uint16_t value() const { return static_cast<std::uint16_t>(crc_ ^ 0xFFFFu); }
  void reset() { crc_ = 0xFFFF; }

 private:
  std::uint16_t crc_ = 0xFFFF;  // CRC register before the final XOR
};

}  // namespace sercon::wire

// How many line bits a telegram takes (flags and bit stuffing included), without encoding
// it: the transmitter's burst_duration() and the receiver's "address is in" moment.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

namespace sercon::chip {

// Line bits of flag, address, data, FCS, flag, exactly as wire::LineEncoder writes them.
std::size_t telegram_line_bits(std::uint8_t address, std::span<const std::uint8_t> data);

namespace line_length_detail {

// address_end_bit() of every address, worked out at compile time: an own telegram's seeded
// decode asks it at every send.
inline constexpr auto kAddressEndBits = [] {
  std::array<std::uint8_t, 256> table{};
  for (unsigned address = 0; address < 256; ++address) {
    unsigned bits = 8 + 8;  // the opening flag and the address byte
    unsigned run = 0;
    for (unsigned bit = 0; bit < 7; ++bit) {  // a 0 stuffed after bit 7 comes after the address
      run = ((address >> bit) & 1u) != 0 ? run + 1 : 0;
      if (run == 5) {
        ++bits;
        run = 0;
      }
    }
    table[address] = static_cast<std::uint8_t>(bits);
  }
  return table;
}();

}  // namespace line_length_detail

// Line bits from the first bit of the opening flag through the last bit of the address
// byte (a 0 stuffed after it is not counted: the address is known without it).
inline std::size_t address_end_bit(std::uint8_t address) {
  return line_length_detail::kAddressEndBits[address];
}

}  // namespace sercon::chip

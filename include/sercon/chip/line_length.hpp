// How many line bits a telegram takes (flags and bit stuffing included), without encoding
// it: the transmitter's burst_duration() and the receiver's "address is in" moment.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>

namespace sercon::chip {

// Line bits of flag, address, data, FCS, flag, exactly as wire::LineEncoder writes them.
std::size_t telegram_line_bits(std::uint8_t address, std::span<const std::uint8_t> data);

// Line bits from the first bit of the opening flag through the last bit of the address
// byte (a 0 stuffed after it is not counted: the address is known without it).
std::size_t address_end_bit(std::uint8_t address);

}  // namespace sercon::chip

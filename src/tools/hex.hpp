// Bytes as the decode output prints them: lowercase hex, two digits a byte, no spaces.
#pragma once

#include <cstdint>
#include <span>
#include <string>

namespace sercon::tools {

std::string to_hex(std::span<const std::uint8_t> bytes);
std::string to_hex16(std::uint16_t value);  // four digits

}  // namespace sercon::tools

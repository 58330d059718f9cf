// SERCOS lines built with the wire encoder, with what a decoder must report for each
// frame on them: the expectations come from the encoder's bit positions, not from sercon
// decode, so the end-to-end tests check it independently.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "sercon/wire/line_bits.hpp"

namespace sercon::testing {

struct ExpectedFrame {
  std::size_t start_bit = 0;  // first line bit of the opening flag
  std::uint8_t address = 0;
  std::vector<std::uint8_t> data;
  std::string kind;               // "MST", "MDT", "AT", "AT/MDT", "ADDR0"; "" for broken frames
  std::optional<unsigned> phase;  // MSTs
  std::string error;              // JSON error class; "" for a good telegram
};

struct TestLine {
  wire::LineBits bits;
  std::vector<ExpectedFrame> frames;
};

// Every kind and phase: MSTs for CP0..CP4, an invalid phase 5, addressed telegrams in
// each phase, an address-0 telegram and a broadcast MDT.
TestLine phase_walk_line();

// Good telegrams with one frame of each error class between them: bad FCS, abort,
// too short, misaligned, and a truncated frame at the end.
TestLine error_line();

// Hex string of bytes, as the decode output prints them.
std::string hex(const std::vector<std::uint8_t>& bytes);

}  // namespace sercon::testing

// The `bits` capture format: line levels, one bit per line bit, packed MSB first, as a
// deserialiser or an FPGA dump gives them. It carries no timing: the bit rate comes from
// the user.
#pragma once

#include <filesystem>

#include "sercon/wire/line_bits.hpp"

namespace sercon::capture {

// Every bit of the file, 8 x its size. Throws CaptureError when the file cannot be read
// or is empty.
wire::LineBits read_bits_file(const std::filesystem::path& file);

// Writes `bits` in the same format; the last byte is padded with 0 bits.
void write_bits_file(const std::filesystem::path& file, const wire::LineBits& bits);

}  // namespace sercon::capture

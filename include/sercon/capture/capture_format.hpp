// The capture file formats `sercon decode` reads, and how a format is chosen.
#pragma once

#include <filesystem>
#include <optional>
#include <string_view>

namespace sercon::capture {

enum class CaptureFormat {
  Bits,  // line levels, one bit per line bit, packed MSB first
  Vcd,   // value change dump, one 1-bit signal
  Sr,    // sigrok session file (zip), one logic channel
};

std::string_view format_name(CaptureFormat format);

// "bits", "vcd" or "sr"; nullopt for anything else.
std::optional<CaptureFormat> parse_format(std::string_view name);

// From the file's extension: .bits/.bin -> Bits, .vcd -> Vcd, .sr -> Sr (case-insensitive).
// Throws CaptureError naming the extension and the --format option otherwise.
CaptureFormat format_from_extension(const std::filesystem::path& file);

}  // namespace sercon::capture

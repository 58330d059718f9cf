#include "sercon/capture/capture_format.hpp"

#include <algorithm>
#include <cctype>
#include <string>

#include "sercon/capture/capture_error.hpp"

namespace sercon::capture {

std::string_view format_name(CaptureFormat format) {
  switch (format) {
    case CaptureFormat::Bits:
      return "bits";
    case CaptureFormat::Vcd:
      return "vcd";
    case CaptureFormat::Sr:
      return "sr";
  }
  return "?";
}

std::optional<CaptureFormat> parse_format(std::string_view name) {
  if (name == "bits") return CaptureFormat::Bits;
  if (name == "vcd") return CaptureFormat::Vcd;
  if (name == "sr") return CaptureFormat::Sr;
  return std::nullopt;
}

CaptureFormat format_from_extension(const std::filesystem::path& file) {
  std::string ext = file.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (ext == ".bits" || ext == ".bin") return CaptureFormat::Bits;
  if (ext == ".vcd") return CaptureFormat::Vcd;
  if (ext == ".sr") return CaptureFormat::Sr;
  const std::string problem =
      ext.empty() ? std::string("it has no extension") : "unknown extension '" + ext + "'";
  throw CaptureError("cannot tell the format of " + file.string() + ": " + problem +
                     " (known: .bits, .bin, .vcd, .sr); name it with --format bits|vcd|sr");
}

}  // namespace sercon::capture

#include "sercon/capture/bits_file.hpp"

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

#include "sercon/capture/capture_error.hpp"
#include "sercon/capture/input_file.hpp"

namespace sercon::capture {
namespace {

// Any byte string is valid line bits, so a capture of another format would decode as noise:
// recognise the two other formats by their first bytes and say so instead.
void reject_other_formats(const std::filesystem::path& file,
                          const std::vector<std::uint8_t>& bytes) {
  const std::string head(
      bytes.begin(),
      bytes.begin() + static_cast<std::ptrdiff_t>(std::min<std::size_t>(bytes.size(), 256)));
  if (head.rfind("PK\x03\x04", 0) == 0) {
    throw CaptureError(
        file.string() +
        " is a zip archive (a sigrok session?), not packed line bits; use --format sr");
  }
  const bool text = std::all_of(head.begin(), head.end(), [](char c) {
    const auto u = static_cast<unsigned char>(c);
    return (u >= 0x20 && u < 0x7F) || c == '\n' || c == '\r' || c == '\t';
  });
  for (const char* keyword : {"$timescale", "$var", "$scope", "$date", "$version", "$comment"}) {
    if (text && head.find(keyword) != std::string::npos) {
      throw CaptureError(file.string() +
                         " is a VCD text file, not packed line bits; use --format vcd");
    }
  }
}

}  // namespace

wire::LineBits read_bits_file(const std::filesystem::path& file) {
  std::ifstream in = open_capture_file(file);
  std::vector<std::uint8_t> bytes;
  std::vector<char> block(64 * 1024);
  while (in.read(block.data(), static_cast<std::streamsize>(block.size())) || in.gcount() > 0) {
    const auto n = static_cast<std::size_t>(in.gcount());
    bytes.insert(bytes.end(), block.begin(), block.begin() + static_cast<std::ptrdiff_t>(n));
  }
  if (in.bad()) throw CaptureError("cannot read " + file.string() + ": " + std::strerror(errno));
  if (bytes.empty()) throw CaptureError(file.string() + " is empty: no line bits to decode");
  reject_other_formats(file, bytes);
  const std::size_t bit_count = bytes.size() * 8;
  return wire::LineBits::from_packed(std::move(bytes), bit_count);
}

void write_bits_file(const std::filesystem::path& file, const wire::LineBits& bits) {
  std::ofstream out(file, std::ios::binary | std::ios::trunc);
  const auto packed = bits.packed();
  out.write(reinterpret_cast<const char*>(packed.data()),
            static_cast<std::streamsize>(packed.size()));
  if (!out) throw CaptureError("cannot write " + file.string() + ": " + std::strerror(errno));
}

}  // namespace sercon::capture

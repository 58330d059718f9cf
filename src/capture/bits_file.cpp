#include "sercon/capture/bits_file.hpp"

#include <cerrno>
#include <cstring>
#include <fstream>
#include <iterator>
#include <vector>

#include "input_file.hpp"
#include "sercon/capture/capture_error.hpp"

namespace sercon::capture {

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

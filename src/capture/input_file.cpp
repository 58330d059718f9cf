#include "sercon/capture/input_file.hpp"

#include <cerrno>
#include <cstring>
#include <system_error>

#include "sercon/capture/capture_error.hpp"

namespace sercon::capture {

void check_readable_file(const std::filesystem::path& file) {
  std::error_code ec;
  const auto status = std::filesystem::status(file, ec);
  if (ec || !std::filesystem::exists(status)) {
    throw CaptureError("cannot read " + file.string() + ": " +
                       (ec ? ec.message() : std::string("no such file")));
  }
  if (std::filesystem::is_directory(status)) {
    throw CaptureError("cannot read " + file.string() + ": it is a directory, not a capture file");
  }
  if (!std::filesystem::is_regular_file(status)) {
    throw CaptureError("cannot read " + file.string() + ": not a regular file");
  }
}

std::ifstream open_capture_file(const std::filesystem::path& file) {
  check_readable_file(file);
  std::ifstream in(file, std::ios::binary);
  if (!in) throw CaptureError("cannot open " + file.string() + ": " + std::strerror(errno));
  return in;
}

}  // namespace sercon::capture

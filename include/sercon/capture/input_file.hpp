// Opening a capture file with errors that say what is wrong with the path.
#pragma once

#include <filesystem>
#include <fstream>

namespace sercon::capture {

// Throws CaptureError when `file` does not exist, is not a regular file, or cannot be read.
void check_readable_file(const std::filesystem::path& file);

// check_readable_file(), then opens it for binary reading.
std::ifstream open_capture_file(const std::filesystem::path& file);

}  // namespace sercon::capture

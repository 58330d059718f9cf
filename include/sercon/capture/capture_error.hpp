// The one exception the capture readers throw: the file cannot be read as the capture it
// claims to be. The message names the file, the problem and, where it helps, the fix.
#pragma once

#include <stdexcept>
#include <string>

namespace sercon::capture {

class CaptureError : public std::runtime_error {
 public:
  explicit CaptureError(const std::string& message) : std::runtime_error(message) {}
};

}  // namespace sercon::capture

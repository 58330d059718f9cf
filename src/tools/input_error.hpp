// Bad command-line input that CLI11 cannot check by itself (a bit rate SERCOS does not
// have, a format that needs an option). The message names the problem.
#pragma once

#include <stdexcept>
#include <string>

namespace sercon::tools {

class InputError : public std::runtime_error {
 public:
  explicit InputError(const std::string& message) : std::runtime_error(message) {}
};

}  // namespace sercon::tools

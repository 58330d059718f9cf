// What `sercon decode` was asked to do, as parsed from the command line.
#pragma once

#include <filesystem>
#include <optional>
#include <string>

#include "sercon/capture/capture_format.hpp"

namespace sercon::tools {

struct DecodeOptions {
  std::filesystem::path file;
  std::optional<capture::CaptureFormat> format;  // --format; unset: from the extension
  std::optional<std::string> rate;               // --rate as typed
  std::string signal;                            // --signal; empty: the only candidate
  bool json = false;
};

}  // namespace sercon::tools

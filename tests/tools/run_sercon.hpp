// Runs the real `sercon` binary (path from CMake) as a process, as a user would.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace sercon::testing {

struct RunResult {
  int status = -1;  // exit status; -1 if the process did not exit normally
  std::string out;
  std::string err;
};

RunResult run_sercon(const std::vector<std::string>& args);

// Every line of `out` parsed as JSON (JSON Lines); a line that is not JSON fails the test.
std::vector<nlohmann::json> json_lines(const std::string& out);

// The repository root, for the shipped captures.
std::string source_dir();

}  // namespace sercon::testing

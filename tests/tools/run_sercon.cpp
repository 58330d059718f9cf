#include "run_sercon.hpp"

#include <gtest/gtest.h>

#include <sstream>

#include "test_files.hpp"

namespace sercon::testing {

RunResult run_sercon(const std::vector<std::string>& args) {
  const TempDir dir;
  // Appended piece by piece: GCC 12 -O3 warns falsely (-Wrestrict) on " " + std::string.
  std::string command = shell_quote(SERCON_BINARY);
  for (const std::string& a : args) command.append(" ").append(shell_quote(a));
  command.append(" >").append(shell_quote((dir / "out").string()));
  command.append(" 2>").append(shell_quote((dir / "err").string()));
  RunResult result;
  result.status = run_command(command);
  result.out = read_file(dir / "out");
  result.err = read_file(dir / "err");
  return result;
}

std::vector<nlohmann::json> json_lines(const std::string& out) {
  std::vector<nlohmann::json> lines;
  std::istringstream in(out);
  for (std::string line; std::getline(in, line);) {
    try {
      lines.push_back(nlohmann::json::parse(line));
    } catch (const nlohmann::json::parse_error& e) {
      ADD_FAILURE() << "not JSON: " << line << " (" << e.what() << ")";
    }
  }
  return lines;
}

std::string source_dir() { return SERCON_SOURCE_DIR; }

}  // namespace sercon::testing

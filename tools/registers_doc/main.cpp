// registers_doc: writes or checks the generated register table in docs/registers.md.
//   registers_doc print          the generated part, to stdout
//   registers_doc check FILE     exit 1 when FILE's generated part differs from the code
//   registers_doc write FILE     replace FILE's generated part (the prose around it stays)
#include <cstdio>
#include <exception>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <string_view>

#include "sercon/chip/register_doc.hpp"

namespace {

std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot read " + path);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// The first line where `a` and `b` differ (1-based), for the error message.
std::size_t first_difference(std::string_view a, std::string_view b) {
  std::size_t line = 1;
  for (std::size_t i = 0; i < a.size() && i < b.size(); ++i) {
    if (a[i] != b[i]) return line;
    if (a[i] == '\n') ++line;
  }
  return line;
}

int usage() {
  std::cerr << "usage: registers_doc print | check FILE | write FILE\n";
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    if (argc < 2) return usage();
    const std::string_view command = argv[1];
    const std::string generated = sercon::chip::register_table_markdown();
    if (command == "print" && argc == 2) {
      std::cout << generated;
      return 0;
    }
    if (argc != 3 || (command != "check" && command != "write")) return usage();
    const std::string path = argv[2];
    const std::string current = read_file(path);
    const std::string wanted = sercon::chip::replace_generated_part(current, generated);
    if (command == "check") {
      if (current == wanted) {
        std::cout << path << ": register table up to date\n";
        return 0;
      }
      std::cerr << path << ": the register table differs from src/chip/register_map.cpp (line "
                << first_difference(current, wanted) << "); run: registers_doc write " << path
                << "\n";
      return 1;
    }
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out << wanted;
    if (!out) throw std::runtime_error("cannot write " + path);
    std::cout << path << ": register table written\n";
    return 0;
  } catch (const std::exception& e) {
    std::cerr << "registers_doc: " << e.what() << "\n";
    return 1;
  }
}

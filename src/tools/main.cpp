// `sercon`: the command line of the SERCON816 model. Each subcommand lives in its own
// *_command.cpp and registers itself here.
#include <CLI/CLI.hpp>

#include <iostream>
#include <optional>
#include <string>
#include <vector>

#include "decode_command.hpp"

namespace {

// CLI11 reports a mistyped subcommand (`sercon decod x.bits`, `sercon --bogus`) as "A
// subcommand is required"; this names the word that was not one instead.
std::optional<std::string> unknown_subcommand(const CLI::App& app) {
  if (!app.get_subcommands().empty()) return std::nullopt;
  const std::vector<std::string> left = app.remaining();
  if (left.empty()) return std::nullopt;  // no argument at all: CLI11's message says it
  std::string known;
  for (const CLI::App* sub : app.get_subcommands({})) {
    known += (known.empty() ? "" : ", ") + sub->get_name();
  }
  const std::string& word = left.front();
  if (word.starts_with('-')) {
    return "unknown option '" + word + "' and no subcommand (subcommands: " + known + ")";
  }
  return "unknown subcommand '" + word + "' (subcommands: " + known + ")";
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"sercon: a model of the SERCON816 SERCOS II interface controller", "sercon"};
  app.require_subcommand(1);
  app.footer("Run `sercon SUBCOMMAND --help` for the options of each subcommand.");
  sercon::tools::add_decode_command(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::RuntimeError& e) {
    return e.get_exit_code();  // a subcommand failed and has said why
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return app.exit(e);  // --help
    // A malformed command line: one message in the house form, and status 2 (as
    // getopt-style tools do), so scripts can tell it from bad input (1).
    std::cerr << "sercon: error: " << unknown_subcommand(app).value_or(e.what())
              << "\nRun `sercon --help` for usage.\n";
    return 2;
  }
  return 0;
}

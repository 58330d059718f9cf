// `sercon`: the command line of the SERCON816 model. Each subcommand lives in its own
// *_command.cpp and registers itself here.
#include <CLI/CLI.hpp>

#include "decode_command.hpp"

int main(int argc, char** argv) {
  CLI::App app{"sercon: a model of the SERCON816 SERCOS II interface controller", "sercon"};
  app.require_subcommand(1);
  app.footer("Run `sercon SUBCOMMAND --help` for the options of each subcommand.");
  sercon::tools::add_decode_command(app);
  CLI11_PARSE(app, argc, argv);
  return 0;
}

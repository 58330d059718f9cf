// `sercon decode`: reads a line capture (bits, VCD or sigrok session) and prints every
// telegram on it with a summary (docs/decode.md).
#pragma once

#include <iosfwd>

#include <CLI/CLI.hpp>

#include "decode_options.hpp"

namespace sercon::tools {

// Adds the `decode` subcommand to `app`; it runs from the subcommand's callback and ends
// parsing with CLI::RuntimeError carrying its exit status when that is not 0.
void add_decode_command(CLI::App& app);

// The decode itself: output on `out`, problems on `err`. Returns the exit status: 0 for a
// readable capture (even with broken telegrams), 1 for bad input or an `out` that failed
// (2, from main, for a malformed command line).
int run_decode(const DecodeOptions& options, std::ostream& out, std::ostream& err);

}  // namespace sercon::tools

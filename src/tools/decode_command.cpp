#include "decode_command.hpp"

#include <cerrno>
#include <cstring>
#include <iostream>
#include <memory>
#include <string>

#include "bit_rate.hpp"
#include "capture_loader.hpp"
#include "decode_summary.hpp"
#include "input_error.hpp"
#include "json_output.hpp"
#include "sercon/capture/capture_error.hpp"
#include "sercon/wire/decoder.hpp"
#include "telegram_classifier.hpp"
#include "text_output.hpp"

namespace sercon::tools {
namespace {

DecodeRunInfo run_info(const DecodeOptions& options, const LoadedCapture& capture) {
  DecodeRunInfo info;
  info.file = options.file.string();
  info.format = capture.format;
  info.bit_period_ps = capture.line.bit_period_ps;
  info.rate_given = capture.rate_given;
  info.signal = capture.signal;
  info.line_bits = capture.line.bits.size();
  info.unknown_values = capture.unknown_values;
  return info;
}

int decode_loaded(const DecodeOptions& options, const LoadedCapture& capture, std::ostream& out,
                  std::ostream& err) {
  const DecodeRunInfo info = run_info(options, capture);
  TelegramClassifier classifier;
  DecodeSummary summary;
  // The reason of the first failed write, taken at once: errno of later calls says nothing.
  int write_error = 0;
  const auto note_write = [&] {
    if (!out && write_error == 0) write_error = errno != 0 ? errno : EIO;
  };
  errno = 0;
  if (!options.json) out << text_header(info);
  note_write();

  wire::LineDecoder decoder([&](const wire::DecodedFrame& frame) {
    const TelegramRow row = classifier.classify(frame, capture.time_from_start_ps(frame.start_bit));
    summary.add(row);
    if (options.json) {
      out << json_row(row).dump() << '\n';
    } else {
      out << text_row(row) << '\n';
    }
    note_write();
  });
  decoder.feed(capture.line.bits);
  decoder.finish();

  if (options.json) {
    out << json_summary(summary, info).dump() << '\n';
  } else {
    out << text_summary(summary, info);
  }
  out.flush();
  note_write();
  // A listing lost on a full disk or a closed stdout must not pass for a decode that worked.
  if (write_error != 0) {
    err << "sercon decode: error: cannot write the output: " << std::strerror(write_error) << '\n';
    return 1;
  }
  if (summary.telegrams() + summary.errors() == 0) {
    err << "sercon decode: error: no SERCOS frame found in " << info.file << " (" << info.line_bits
        << " line bits at " << describe_bit_period(info.bit_period_ps)
        << "): is it a SERCOS line capture, and is the rate right?\n";
    return 1;
  }
  return 0;
}

}  // namespace

int run_decode(const DecodeOptions& options, std::ostream& out, std::ostream& err) {
  try {
    const LoadedCapture capture = load_capture(options);
    return decode_loaded(options, capture, out, err);
  } catch (const std::exception& e) {
    // CaptureError, RecoveryError and InputError all carry a message for the user;
    // anything else (out of memory) is reported the same way rather than crashing.
    err << "sercon decode: error: " << e.what() << '\n';
    return 1;
  }
}

void add_decode_command(CLI::App& app) {
  auto options = std::make_shared<DecodeOptions>();
  auto format = std::make_shared<std::string>();
  CLI::App* decode = app.add_subcommand(
      "decode", "Decode the SERCOS II telegrams on a line capture (bits, VCD, sigrok)");
  decode->footer(
      "Prints one line per telegram (time in ns from the capture start, kind, address, length,\n"
      "data in hex, FCS status; MSTs also the phase), broken frames with error=CLASS, then a\n"
      "summary. Exit status 0 for a readable capture, even with broken telegrams; 1 for bad\n"
      "input or output that cannot be written; 2 for a malformed command line. See\n"
      "docs/decode.md.\n\n"
      "Examples:\n"
      "  sercon decode --rate 4M captures/phase-up-4drives.bits\n"
      "  sercon decode captures/cp4-excerpt.vcd\n"
      "  sercon decode --json --signal D0 capture.sr");

  decode->add_option("FILE", options->file, "Capture file (.bits, .vcd or .sr)")
      ->required()
      ->type_name("");
  decode
      ->add_option("--format", *format,
                   "Capture format: bits (line levels packed MSB first), vcd (one 1-bit "
                   "signal), sr (sigrok session, one logic channel). Default: from the "
                   "file extension (.bits/.bin, .vcd, .sr)")
      ->check(CLI::IsMember({"bits", "vcd", "sr"}))
      ->type_name("FORMAT");
  decode
      ->add_option("--rate", options->rate,
                   "Bit rate: 2M, 4M, 8M or 16M. Required for bits; detected from the "
                   "capture for vcd and sr when not given")
      ->type_name("RATE");
  decode
      ->add_option("--signal", options->signal,
                   "VCD signal (name or scope.name) or sigrok channel to decode. Default: "
                   "the only 1-bit signal / logic channel")
      ->type_name("NAME");
  decode->add_flag("--json", options->json,
                   "JSON Lines: one object per telegram, the last line {\"summary\": ...}");

  decode->callback([options, format] {
    options->format = capture::parse_format(*format);
    const int status = run_decode(*options, std::cout, std::cerr);
    if (status != 0) throw CLI::RuntimeError(status);
  });
}

}  // namespace sercon::tools

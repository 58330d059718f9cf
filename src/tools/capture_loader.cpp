#include "capture_loader.hpp"

#include "bit_rate.hpp"
#include "input_error.hpp"
#include "sercon/capture/bits_file.hpp"
#include "sercon/capture/input_file.hpp"
#include "sercon/capture/sr_reader.hpp"
#include "sercon/capture/vcd_reader.hpp"

namespace sercon::tools {
namespace {

std::string ns_text(std::int64_t ps) {
  const std::string whole = std::to_string(ps / 1000);
  const std::int64_t frac = ps % 1000;
  if (frac == 0) return whole + " ns";
  std::string digits = std::to_string(1000 + frac).substr(1);
  while (digits.back() == '0') digits.pop_back();
  return whole + "." + digits + " ns";
}

// 1e12 / rate ps as ns, to the picosecond: "125 ns", "41.667 ns" (24 MHz, rounded).
std::string sample_period_text(std::uint64_t rate_hz) {
  const std::uint64_t ps_per_second = 1'000'000'000'000;
  return ns_text(static_cast<std::int64_t>((ps_per_second + rate_hz / 2) / rate_hz));
}

wire::RecoveryOptions recovery_options(const std::optional<std::int64_t>& period_ps) {
  wire::RecoveryOptions options;
  options.bit_period_ps = period_ps;
  return options;
}

// Wraps a clock-recovery failure so the message says which signal it was about, and how
// to give the rate when detection failed.
template <typename Recover>
wire::RecoveredLine recover(const std::string& what, bool rate_given, Recover&& run) {
  try {
    return run();
  } catch (const wire::RecoveryError& e) {
    throw wire::RecoveryError("cannot recover the bit clock from " + what + ": " + e.what() +
                              (rate_given ? "" : " (sercon decode: --rate 2M|4M|8M|16M)"));
  }
}

void load_bits(const DecodeOptions& options, const std::optional<std::int64_t>& period_ps,
               LoadedCapture& out) {
  if (!period_ps) {
    throw InputError(
        "the bits format carries no timing: give the bit rate with --rate 2M|4M|8M|16M");
  }
  out.line.bits = capture::read_bits_file(options.file);
  out.line.bit_period_ps = *period_ps;
  out.line.anchors = {{0, 0}};
}

void load_vcd(const DecodeOptions& options, const std::optional<std::int64_t>& period_ps,
              LoadedCapture& out) {
  const capture::VcdTrace trace = capture::read_vcd_file(options.file, options.signal);
  out.signal = trace.variable.full_name();
  out.start_ps = trace.start_ps;
  out.unknown_values = trace.unknown_values;
  out.line = recover("VCD signal '" + out.signal + "'", period_ps.has_value(), [&] {
    return wire::recover_from_edges(trace.initial_level, trace.edges, trace.start_ps, trace.end_ps,
                                    recovery_options(period_ps));
  });
}

void load_sr(const DecodeOptions& options, const std::optional<std::int64_t>& period_ps,
             LoadedCapture& out) {
  const capture::SrChannel channel = capture::read_sr_file(options.file, options.signal);
  out.signal = channel.name;
  // The receiver needs at least two samples per bit to see every level between edges:
  // 2 * 1e12 / rate <= period, in integers (rate <= 1 THz, period <= 500 000 ps).
  if (period_ps &&
      2'000'000'000'000 > static_cast<std::uint64_t>(*period_ps) * channel.samplerate_hz) {
    throw InputError("impossible bit rate " + describe_bit_period(*period_ps) + " for " +
                     options.file.string() + ": it is sampled every " +
                     sample_period_text(channel.samplerate_hz) + ", and decoding needs at least " +
                     "2 samples per bit (" + ns_text(*period_ps) + ")");
  }
  // The exact rate, not a period rounded to the picosecond: a 24 MHz capture keeps its
  // times to the end (docs/wire.md).
  out.line = recover("sigrok channel '" + out.signal + "'", period_ps.has_value(), [&] {
    return wire::recover_from_samples(channel.samples, channel.sample_count,
                                      wire::SampleRate{channel.samplerate_hz}, 0,
                                      recovery_options(period_ps));
  });
}

}  // namespace

LoadedCapture load_capture(const DecodeOptions& options) {
  LoadedCapture out;
  capture::check_readable_file(options.file);
  out.format = options.format ? *options.format : capture::format_from_extension(options.file);
  std::optional<std::int64_t> period_ps;
  if (options.rate) period_ps = parse_bit_rate(*options.rate);
  out.rate_given = period_ps.has_value();
  if (out.format == capture::CaptureFormat::Bits && !options.signal.empty()) {
    throw InputError("--signal does not apply to the bits format (it holds one line)");
  }
  switch (out.format) {
    case capture::CaptureFormat::Bits:
      load_bits(options, period_ps, out);
      break;
    case capture::CaptureFormat::Vcd:
      load_vcd(options, period_ps, out);
      break;
    case capture::CaptureFormat::Sr:
      load_sr(options, period_ps, out);
      break;
  }
  return out;
}

}  // namespace sercon::tools

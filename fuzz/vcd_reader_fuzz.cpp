// libFuzzer target for the VCD reader: random bytes as a VCD file, with a --rate and a
// --signal name chosen by the input (fuzz/capture_fuzz_input.hpp). Each input goes
//   1. through capture::read_vcd from memory, whose trace must be well formed: levels that
//      alternate, strictly increasing edge times inside the capture, a legal timescale;
//   2. through the path `sercon decode` takes (a file, tools::load_capture, the line
//      decoder), which must agree with 1 on whether the file is a readable VCD.
// Only the documented errors may escape (CaptureError, RecoveryError, InputError); any
// other exception, crash, sanitizer report, hang or runaway allocation is a finding.
#include <cstddef>
#include <cstdint>
#include <sstream>
#include <string>

#include "capture_fuzz_common.hpp"
#include "sercon/capture/vcd_reader.hpp"

namespace {

using namespace sercon;
using fuzz::check;

void check_trace(const capture::VcdTrace& trace) {
  bool legal_timescale = false;
  for (std::int64_t unit : {1LL, 1'000LL, 1'000'000LL, 1'000'000'000LL, 1'000'000'000'000LL})
    for (std::int64_t n : {1LL, 10LL, 100LL}) legal_timescale |= trace.timescale_ps == n * unit;
  check(legal_timescale, "timescale is 1, 10 or 100 of s, ms, us, ns or ps");
  check(trace.variable.is_line_candidate(), "the signal read is a 1-bit line signal");
  check(!trace.edges.empty(), "a trace that is returned has edges");
  check(trace.start_ps <= trace.end_ps, "the capture starts before it ends");
  bool level = trace.initial_level;
  std::int64_t previous = trace.start_ps;
  for (const wire::Edge& e : trace.edges) {
    check(e.level != level, "every edge changes the level");
    check(e.time_ps > previous, "edge times strictly increase, after the start");
    level = e.level;
    previous = e.time_ps;
  }
  check(previous <= trace.end_ps, "edges inside the capture");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const fuzz::FuzzInput in = fuzz::parse_fuzz_input({reinterpret_cast<const char*>(data), size});

  bool reader_ok = false;
  try {
    std::istringstream stream{std::string(in.capture)};
    check_trace(capture::read_vcd(stream, in.signal, "fuzz.vcd"));
    reader_ok = true;
  } catch (const capture::CaptureError&) {
  } catch (const std::exception& e) {
    fuzz::undocumented("read_vcd", e);
  }

  static const fuzz::ScratchFile file(".vcd");
  file.write(in.capture);
  bool capture_error = false;
  const bool loaded =
      fuzz::decode_path(file.path(), capture::CaptureFormat::Vcd, in, &capture_error);
  check(!loaded || reader_ok, "sercon decode loaded a VCD that read_vcd refused");
  check(!(reader_ok && capture_error), "sercon decode refused a VCD that read_vcd read");
  return 0;
}

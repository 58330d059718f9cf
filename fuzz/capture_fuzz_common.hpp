// What the capture reader fuzz targets share: a scratch file per process (the readers and
// `sercon decode` read files), the decode path of `sercon decode` (tools::load_capture, then
// the line decoder), and the invariants of its result.
#pragma once

#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <string>
#include <string_view>

#include "capture_fuzz_input.hpp"
#include "capture_loader.hpp"
#include "input_error.hpp"
#include "sercon/capture/capture_error.hpp"
#include "sercon/wire/clock_recovery.hpp"
#include "sercon/wire/decoder.hpp"

namespace sercon::fuzz {

inline void check(bool ok, const char* what) {
  if (!ok) {
    std::fprintf(stderr, "capture fuzz: invariant violated: %s\n", what);
    std::abort();
  }
}

[[noreturn]] inline void undocumented(const char* where, const std::exception& e) {
  std::fprintf(stderr, "capture fuzz: %s threw an undocumented exception: %s\n", where, e.what());
  std::abort();
}

// A file of this process in /dev/shm (memory, when there is one) or the temp directory,
// removed when the process ends normally.
class ScratchFile {
 public:
  explicit ScratchFile(std::string_view extension)
      : path_((std::filesystem::is_directory("/dev/shm") ? std::filesystem::path("/dev/shm")
                                                         : std::filesystem::temp_directory_path()) /
              ("sercon-fuzz-" + std::to_string(::getpid()) + std::string(extension))) {}
  ~ScratchFile() {
    std::error_code ec;
    std::filesystem::remove(path_, ec);
  }
  ScratchFile(const ScratchFile&) = delete;
  ScratchFile& operator=(const ScratchFile&) = delete;

  const std::filesystem::path& path() const { return path_; }

  void write(std::string_view bytes) const {
    std::FILE* f = std::fopen(path_.c_str(), "wb");
    check(f != nullptr, "scratch file can be written");
    check(std::fwrite(bytes.data(), 1, bytes.size(), f) == bytes.size(), "scratch file written");
    std::fclose(f);
  }

 private:
  std::filesystem::path path_;
};

// The loaded capture as `sercon decode` has it: a SERCOS bit period, anchors in order and
// inside the line, and frames from the decoder inside the line, in order.
inline void check_loaded(const tools::LoadedCapture& capture, const FuzzInput& in) {
  const wire::RecoveredLine& line = capture.line;
  bool standard = false;
  for (std::int64_t p : wire::kBitPeriodsPs) standard = standard || p == line.bit_period_ps;
  check(standard, "the bit period is a SERCOS rate's");
  check(capture.rate_given == in.rate.has_value(), "rate_given says whether --rate was given");
  check(!line.anchors.empty(), "a recovered line has anchors");
  for (std::size_t i = 1; i < line.anchors.size(); ++i) {
    check(line.anchors[i].bit > line.anchors[i - 1].bit, "anchor bits strictly increase");
    check(line.anchors[i].time_ps >= line.anchors[i - 1].time_ps, "anchor times do not go back");
  }
  check(line.anchors.back().bit <= line.bits.size(), "anchors inside the line");

  std::size_t last_start = 0;
  std::size_t frames = 0;
  wire::LineDecoder decoder([&](const wire::DecodedFrame& f) {
    check(f.start_bit >= last_start, "frames in order");
    check(f.start_bit <= f.end_bit && f.end_bit <= line.bits.size(), "frame inside the line");
    (void)capture.time_from_start_ps(f.start_bit);
    last_start = f.start_bit;
    ++frames;
  });
  decoder.feed(line.bits);
  decoder.finish();
}

// Runs the decode path on `file` as `sercon decode --format FORMAT [--rate] [--signal]`
// would. Returns true when the capture loaded; false for a documented error. Any other
// exception is a finding.
inline bool decode_path(const std::filesystem::path& file, capture::CaptureFormat format,
                        const FuzzInput& in, bool* capture_error = nullptr) {
  tools::DecodeOptions options;
  options.file = file;
  options.format = format;
  options.rate = in.rate;
  options.signal = in.signal;
  try {
    const tools::LoadedCapture capture = tools::load_capture(options);
    check_loaded(capture, in);
    return true;
  } catch (const capture::CaptureError&) {
    if (capture_error != nullptr) *capture_error = true;
  } catch (const wire::RecoveryError&) {
  } catch (const tools::InputError&) {
  } catch (const std::exception& e) {
    undocumented("load_capture", e);
  }
  return false;
}

}  // namespace sercon::fuzz

// Reads one logic channel of a sigrok session file (.sr, format version 1 or 2) as the
// packed 1-bit samples that the wire layer's sample-based clock recovery takes.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace sercon::capture {

struct SrChannel {
  std::string name;                 // the probe's name in the session
  std::uint64_t samplerate_hz = 0;  // the timing: sample k is at k * 1e12 / samplerate_hz ps
  // 1e12 / samplerate rounded to whole picoseconds, for messages only: 24 MHz is
  // 41 666.67 ps, so times from the rounded period would drift (use samplerate_hz).
  std::int64_t sample_period_ps = 0;
  std::uint64_t sample_count = 0;
  std::vector<std::uint64_t> samples;  // sample k is bit k % 64 of word k / 64
};

// The most samples read from a session: 2^33 (1 GiB of packed samples; 6 minutes at
// 24 MHz). The zip's deflated data can expand a thousandfold, so a small file could
// otherwise ask for gigabytes.
inline constexpr std::uint64_t kMaxSrSamples = std::uint64_t{1} << 33;

// `signal` is a probe name; empty means "the only logic probe". Throws CaptureError when
// the file is not a readable sigrok session, the probe is missing or ambiguous, the data is
// truncated or holds more than `max_samples` samples, or the channel never changes level.
SrChannel read_sr_file(const std::filesystem::path& file, std::string_view signal,
                       std::uint64_t max_samples = kMaxSrSamples);

}  // namespace sercon::capture

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
  std::string name;  // the probe's name in the session
  std::uint64_t samplerate_hz = 0;
  std::int64_t sample_period_ps = 0;  // 1e12 / samplerate, rounded to whole picoseconds
  std::uint64_t sample_count = 0;
  std::vector<std::uint64_t> samples;  // sample k is bit k % 64 of word k / 64
};

// `signal` is a probe name; empty means "the only logic probe". Throws CaptureError when
// the file is not a readable sigrok session, the probe is missing or ambiguous, the data is
// truncated, or the channel never changes level.
SrChannel read_sr_file(const std::filesystem::path& file, std::string_view signal);

}  // namespace sercon::capture

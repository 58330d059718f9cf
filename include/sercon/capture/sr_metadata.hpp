// The `metadata` file of a sigrok session (an INI file), as far as decoding needs it.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace sercon::capture {

struct SrProbe {
  unsigned number = 0;  // probeN: 1-based; its level is bit N-1 of each sample
  std::string name;
};

struct SrMetadata {
  std::string capturefile;  // base name of the logic data entries, "logic-1"
  std::uint64_t samplerate_hz = 0;
  unsigned total_probes = 0;
  unsigned unitsize = 0;        // bytes per sample
  std::vector<SrProbe> probes;  // the enabled logic probes, by number
};

// "64 MHz", "200 kHz", "1.5 MHz", "1000000", "1 GHz" -> Hz. Throws CaptureError otherwise.
std::uint64_t parse_samplerate(std::string_view text);

// Reads [device 1] (sigrok-cli writes one device). Throws CaptureError for a missing
// section or key, an unusable value, or a probe that does not fit in `unitsize` bytes.
SrMetadata parse_sr_metadata(std::string_view text);

}  // namespace sercon::capture

// The input layout of the capture reader fuzz targets (vcd_reader_fuzz, sr_reader_fuzz),
// shared with the seed corpus generator so that seeds made from real captures are inputs
// the targets understand. Header-only, no dependency on the code under test.
//
//   byte 0          options: bits 0-2 the --rate (0-3: none, detect; 4..7: 2M, 4M, 8M,
//                   16M), bit 3: a --signal name follows, bits 4-7: target-specific
//   [signal '\n']   the --signal name, when bit 3 is set (at most 64 bytes are used)
//   rest            the capture: VCD text, or for sr the zip bytes / the parts of a zip
//
// sr_reader_fuzz, structured mode (option bit 4): the rest is parts separated by
// kPartMarker: the `version` entry, the `metadata` entry, then the logic entries. They are
// zipped with libzip as `logic-1-1`, `logic-1-2`, ... (or one `logic-1` with option bit 5),
// deflated unless option bit 6 is set.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace sercon::fuzz {

inline constexpr std::string_view kPartMarker{"\0SR\0", 4};
inline constexpr std::uint8_t kSignalGiven = 0x08;
inline constexpr std::uint8_t kSrStructured = 0x10;
inline constexpr std::uint8_t kSrSingleEntry = 0x20;
inline constexpr std::uint8_t kSrStored = 0x40;

struct FuzzInput {
  std::uint8_t options = 0;
  std::optional<std::string> rate;  // as typed after --rate
  std::string signal;               // empty: the only candidate
  std::string_view capture;
};

inline FuzzInput parse_fuzz_input(std::string_view bytes) {
  FuzzInput in;
  if (bytes.empty()) return in;
  in.options = static_cast<std::uint8_t>(bytes.front());
  bytes.remove_prefix(1);
  static constexpr const char* kRates[] = {"2M", "4M", "8M", "16M"};
  if ((in.options & 4) != 0) in.rate = kRates[in.options & 3];
  if ((in.options & kSignalGiven) != 0) {
    const std::size_t eol = bytes.find('\n');
    const std::string_view name = bytes.substr(0, eol);
    in.signal = std::string(name.substr(0, 64));
    bytes = eol == std::string_view::npos ? std::string_view{} : bytes.substr(eol + 1);
  }
  in.capture = bytes;
  return in;
}

// The inverse, for the seed generator. `rate` is 0 (detect) or 2, 4, 8, 16 (Mbit/s).
inline std::string make_fuzz_input(std::uint8_t extra_options, int rate_mbit,
                                   std::string_view signal, std::string_view capture) {
  std::uint8_t options = extra_options;
  if (rate_mbit != 0)
    options |= static_cast<std::uint8_t>(4 | (rate_mbit == 2   ? 0
                                              : rate_mbit == 4 ? 1
                                              : rate_mbit == 8 ? 2
                                                               : 3));
  if (!signal.empty()) options |= kSignalGiven;
  std::string out(1, static_cast<char>(options));
  if (!signal.empty()) out.append(signal).append("\n");
  out.append(capture);
  return out;
}

inline std::vector<std::string_view> split_parts(std::string_view bytes) {
  std::vector<std::string_view> parts;
  for (;;) {
    const std::size_t at = bytes.find(kPartMarker);
    parts.push_back(bytes.substr(0, at));
    if (at == std::string_view::npos) return parts;
    bytes.remove_prefix(at + kPartMarker.size());
  }
}

inline std::string join_parts(const std::vector<std::string>& parts) {
  std::string out;
  for (std::size_t i = 0; i < parts.size(); ++i) {
    if (i > 0) out.append(kPartMarker);
    out.append(parts[i]);
  }
  return out;
}

}  // namespace sercon::fuzz

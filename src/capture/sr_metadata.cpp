#include "sercon/capture/sr_metadata.hpp"

#include <algorithm>
#include <cctype>
#include <map>
#include <optional>

#include "sercon/capture/capture_error.hpp"

namespace sercon::capture {
namespace {

std::string_view trim(std::string_view s) {
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front())) != 0) s.remove_prefix(1);
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back())) != 0) s.remove_suffix(1);
  return s;
}

std::optional<std::uint64_t> parse_unsigned(std::string_view s) {
  if (s.empty() || s.size() > 18) return std::nullopt;
  std::uint64_t value = 0;
  for (char c : s) {
    if (c < '0' || c > '9') return std::nullopt;
    value = value * 10 + static_cast<std::uint64_t>(c - '0');
  }
  return value;
}

// 1 THz: one sample per picosecond, the finest time sercon represents.
constexpr std::uint64_t kMaxSamplerateHz = 1'000'000'000'000;

using Section = std::map<std::string, std::string, std::less<>>;

std::map<std::string, Section, std::less<>> parse_ini(std::string_view text) {
  std::map<std::string, Section, std::less<>> sections;
  Section* current = nullptr;
  std::size_t line_number = 0;
  while (!text.empty()) {
    const std::size_t eol = text.find('\n');
    const std::string_view line = trim(text.substr(0, eol));
    text = eol == std::string_view::npos ? std::string_view{} : text.substr(eol + 1);
    ++line_number;
    if (line.empty() || line.front() == '#' || line.front() == ';') continue;
    if (line.front() == '[') {
      if (line.back() != ']') {
        throw CaptureError("session metadata line " + std::to_string(line_number) +
                           ": unterminated section header");
      }
      current = &sections[std::string(trim(line.substr(1, line.size() - 2)))];
      continue;
    }
    const std::size_t eq = line.find('=');
    if (eq == std::string_view::npos || current == nullptr) {
      throw CaptureError("session metadata line " + std::to_string(line_number) +
                         ": expected key=value inside a [section]");
    }
    (*current)[std::string(trim(line.substr(0, eq)))] = std::string(trim(line.substr(eq + 1)));
  }
  return sections;
}

const std::string& required(const Section& device, std::string_view key) {
  const auto it = device.find(key);
  if (it == device.end()) {
    throw CaptureError("session metadata: [device 1] has no '" + std::string(key) + "'");
  }
  return it->second;
}

unsigned required_count(const Section& device, std::string_view key, unsigned max) {
  const std::string& text = required(device, key);
  const auto value = parse_unsigned(text);
  if (!value || *value > max) {
    throw CaptureError("session metadata: bad " + std::string(key) + " '" + text + "'");
  }
  return static_cast<unsigned>(*value);
}

}  // namespace

std::uint64_t parse_samplerate(std::string_view text) {
  const std::string shown = "bad samplerate '" + std::string(text) + "'";
  std::string_view s = trim(text);
  // Units as sigrok prints them; the "Hz" is optional, the prefix case-sensitive (m != M).
  if (s.size() >= 2 && (s.substr(s.size() - 2) == "Hz" || s.substr(s.size() - 2) == "hz")) {
    s.remove_suffix(2);
  }
  s = trim(s);
  std::uint64_t scale = 1;
  if (!s.empty() && (s.back() == 'k' || s.back() == 'K')) scale = 1'000;
  if (!s.empty() && s.back() == 'M') scale = 1'000'000;
  if (!s.empty() && s.back() == 'G') scale = 1'000'000'000;
  if (scale != 1) s = trim(s.substr(0, s.size() - 1));

  const std::size_t dot = s.find('.');
  const std::string_view whole = s.substr(0, dot);
  std::string_view fraction =
      dot == std::string_view::npos ? std::string_view{} : s.substr(dot + 1);
  while (!fraction.empty() && fraction.back() == '0') fraction.remove_suffix(1);
  const auto whole_value = parse_unsigned(whole);
  if (!whole_value || (dot != std::string_view::npos && fraction.empty() && s.size() == dot + 1)) {
    throw CaptureError(shown);
  }
  if (*whole_value > kMaxSamplerateHz / scale) throw CaptureError(shown + ": too high");
  std::uint64_t hz = *whole_value * scale;
  if (!fraction.empty()) {
    const auto fraction_value = parse_unsigned(fraction);
    std::uint64_t divisor = 1;
    for (std::size_t i = 0; i < fraction.size(); ++i) divisor *= 10;
    if (!fraction_value || scale % divisor != 0) throw CaptureError(shown + ": not a whole Hz");
    hz += *fraction_value * (scale / divisor);
  }
  if (hz == 0) throw CaptureError(shown + ": must be above 0 Hz");
  if (hz > kMaxSamplerateHz) throw CaptureError(shown + ": above 1 THz (1 sample per ps)");
  return hz;
}

SrMetadata parse_sr_metadata(std::string_view text) {
  const auto sections = parse_ini(text);
  const auto device_it = sections.find("device 1");
  if (device_it == sections.end()) {
    throw CaptureError("session metadata has no [device 1] section");
  }
  const Section& device = device_it->second;

  SrMetadata meta;
  const auto capturefile = device.find("capturefile");
  if (capturefile == device.end()) {
    throw CaptureError("the sigrok session has no logic data ([device 1] has no capturefile)");
  }
  meta.capturefile = capturefile->second;
  meta.samplerate_hz = parse_samplerate(required(device, "samplerate"));
  meta.unitsize = required_count(device, "unitsize", 8);
  if (meta.unitsize == 0) throw CaptureError("session metadata: unitsize is 0");
  meta.total_probes = required_count(device, "total probes", 64);

  for (const auto& [key, value] : device) {
    if (key.rfind("probe", 0) != 0) continue;
    const auto number = parse_unsigned(std::string_view(key).substr(5));
    if (!number) continue;  // not probeN
    if (*number == 0 || *number > meta.total_probes || *number > meta.unitsize * 8ULL) {
      throw CaptureError("session metadata: " + key + " does not fit " +
                         std::to_string(meta.total_probes) + " probes in " +
                         std::to_string(meta.unitsize) + "-byte samples");
    }
    meta.probes.push_back({static_cast<unsigned>(*number), value});
  }
  std::sort(meta.probes.begin(), meta.probes.end(),
            [](const SrProbe& a, const SrProbe& b) { return a.number < b.number; });
  if (meta.probes.empty()) throw CaptureError("the sigrok session has no logic probes");
  return meta;
}

}  // namespace sercon::capture

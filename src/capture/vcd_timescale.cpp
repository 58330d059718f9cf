#include "sercon/capture/vcd_timescale.hpp"

#include <array>
#include <cctype>
#include <string>
#include <utility>

#include "sercon/capture/capture_error.hpp"

namespace sercon::capture {

std::int64_t parse_vcd_timescale_ps(std::string_view text) {
  std::string compact;  // "1 ns" and "1ns" are both legal VCD
  for (char c : text) {
    if (std::isspace(static_cast<unsigned char>(c)) == 0) compact += c;
  }
  const std::string shown = "$timescale '" + std::string(text) + "'";

  std::size_t digits = 0;
  while (digits < compact.size() && std::isdigit(static_cast<unsigned char>(compact[digits]))) {
    ++digits;
  }
  const std::string number = compact.substr(0, digits);
  const std::string unit = compact.substr(digits);
  std::int64_t multiplier = 0;
  if (number == "1") multiplier = 1;
  if (number == "10") multiplier = 10;
  if (number == "100") multiplier = 100;
  if (multiplier == 0) {
    throw CaptureError(shown + ": the number must be 1, 10 or 100");
  }

  if (unit == "fs") {
    throw CaptureError(shown + " is finer than 1 ps; sercon keeps times in whole picoseconds");
  }
  static constexpr std::array<std::pair<std::string_view, std::int64_t>, 5> kUnits{{
      {"s", 1'000'000'000'000},
      {"ms", 1'000'000'000},
      {"us", 1'000'000},
      {"ns", 1'000},
      {"ps", 1},
  }};
  for (const auto& [name, ps] : kUnits) {
    if (unit == name) return multiplier * ps;
  }
  throw CaptureError(shown + ": the unit must be s, ms, us, ns, ps or fs");
}

}  // namespace sercon::capture

#include "sercon/chip/chip_config.hpp"

#include <stdexcept>
#include <string>

#include "sercon/sim/time.hpp"

namespace sercon::chip {
namespace {

constexpr std::int64_t kMHz = 1'000'000;

void require(bool ok, const std::string& problem) {
  if (!ok) throw std::invalid_argument("ChipConfig: " + problem);
}

// True when a clock of `hz` has a period of a whole number of picoseconds.
bool exact_period(std::int64_t hz) { return hz > 0 && sim::kSecond % hz == 0; }

}  // namespace

void ChipConfig::validate() const {
  require(variant == Variant::Sercon816 || variant == Variant::Sercon410B,
          "unknown variant " + std::to_string(static_cast<int>(variant)));
  require(mclk_hz >= 12 * kMHz && mclk_hz <= 64 * kMHz,
          "MCLK " + std::to_string(mclk_hz) + " Hz is outside 12..64 MHz (datasheet 3.5.1)");
  // Any MCLK in range is exact: edge k is at floor(k * 1e12 / f_MCLK) ps (MclkGrid).
  require(sclk_hz > 0 && sclk_hz <= 64 * kMHz,
          "SCLK " + std::to_string(sclk_hz) + " Hz is outside 1 Hz..64 MHz (datasheet 3.5.2)");
  require(variant != Variant::Sercon816 || sbaud16 || sclk_hz >= 32 * kMHz,
          "SCLK " + std::to_string(sclk_hz) +
              " Hz is below 32 MHz, the minimum with the PLL on (SBAUD16 = 0, datasheet 3.2)");
  // The fastest serial clock is SCLK / 4 (16 Mbit/s at 64 MHz); the slowest SCLK / 32.
  require(sclk_hz % 32 == 0 && exact_period(sclk_hz) && exact_period(sclk_hz / 4),
          "SCLK " + std::to_string(sclk_hz) +
              " Hz does not give whole-picosecond clock and bit times (SCLK and SCLK / 4 "
              "must divide 1e12, SCLK / 32 must be a whole number of Hz)");
  require(variant != Variant::Sercon410B || sbaud16,
          "SERCON410B with SREGEN (pin 28) = 0 selects external clock recovery, which this "
          "model does not implement (delta spec 2.3.2)");
}

}  // namespace sercon::chip

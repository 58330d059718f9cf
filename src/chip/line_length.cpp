#include "sercon/chip/line_length.hpp"

#include <array>

#include "sercon/wire/fcs.hpp"

namespace sercon::chip {
namespace {

constexpr std::size_t kFlagBits = 8;

// Bit stuffing of one byte (LSB first) entered with `run` 1s already in a row (0..4):
// the 0s inserted and the run left over.
struct Stuffing {
  std::uint8_t inserted = 0;
  std::uint8_t run = 0;
};

constexpr Stuffing stuff_byte(unsigned run, unsigned byte) {
  Stuffing s;
  for (unsigned bit = 0; bit < 8; ++bit) {
    run = ((byte >> bit) & 1u) != 0 ? run + 1 : 0;
    if (run == 5) {
      ++s.inserted;
      run = 0;
    }
  }
  s.run = static_cast<std::uint8_t>(run);
  return s;
}

constexpr auto kStuffing = [] {
  std::array<std::array<Stuffing, 256>, 5> table{};
  for (unsigned run = 0; run < 5; ++run) {
    for (unsigned byte = 0; byte < 256; ++byte) table[run][byte] = stuff_byte(run, byte);
  }
  return table;
}();

}  // namespace

std::size_t telegram_line_bits(std::uint8_t address, std::span<const std::uint8_t> data) {
  wire::Fcs16 fcs;
  fcs.update(address);
  fcs.update(data);
  const std::uint16_t check = fcs.value();
  std::size_t bits = 2 * kFlagBits + 8 * (data.size() + 3);
  unsigned run = 0;  // the opening flag ends with a 0
  const auto add = [&](std::uint8_t byte) {
    const Stuffing& s = kStuffing[run][byte];
    bits += s.inserted;
    run = s.run;
  };
  add(address);
  for (const std::uint8_t byte : data) add(byte);
  add(static_cast<std::uint8_t>(check & 0xFFu));  // FCS low byte first
  add(static_cast<std::uint8_t>(check >> 8));
  return bits;
}

}  // namespace sercon::chip

// The two usual ways a board wires the chip into the µP's address space (delta spec 2.5):
// the board's own decoder pulls MCSN0 and PCSN0 low for the chip's window, and one
// address line drives both MCSN1 and PCS1, choosing RAM (line = 0) or registers (1).
#pragma once

#include <cstdint>

#include "sercon/chip/bus.hpp"

namespace sercon::chip {

class Chip;

enum class BoardDecoding : std::uint8_t {
  // SERCON410B boards: A11 selects. RAM at byte offsets 0x000..0x7FF (1K words), registers
  // from 0x800. An 816 on such a board reaches only the lower 1K words of its RAM.
  A11,
  // SERCON816 boards: A12 selects. RAM at 0x0000..0x0FFF (2K words), registers from 0x1000.
  A12,
};

// Bytes of µP address space the chip occupies: 4 KB (A11) or 8 KB (A12).
constexpr std::uint32_t board_window(BoardDecoding d) {
  return d == BoardDecoding::A11 ? 0x1000u : 0x2000u;
}

// The pins a board drives for a µP access at byte `offset` within the chip's window.
// std::out_of_range when `offset` lies outside the window.
BusCycle board_cycle(BoardDecoding d, std::uint16_t offset);

// A µP on such a board: word accesses at byte offsets in the chip's window, made the way
// Chip::reg_read does (one 16-bit cycle, or two byte cycles on an 8-bit bus).
class BoardBus {
 public:
  BoardBus(Chip& chip, BoardDecoding decoding) : chip_(chip), decoding_(decoding) {}

  std::uint16_t read16(std::uint16_t offset);
  void write16(std::uint16_t offset, std::uint16_t value);
  // Byte offset of a RAM word / register word in the window.
  std::uint16_t ram_offset(std::uint16_t word) const;
  std::uint16_t register_offset(std::uint16_t word) const;

 private:
  Chip& chip_;
  BoardDecoding decoding_;
};

}  // namespace sercon::chip

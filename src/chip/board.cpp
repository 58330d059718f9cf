#include "sercon/chip/board.hpp"

#include <stdexcept>
#include <string>

#include "sercon/chip/chip.hpp"

namespace sercon::chip {
namespace {

// The address line that drives MCSN1 and PCS1.
constexpr std::uint16_t select_line(BoardDecoding d) {
  return d == BoardDecoding::A11 ? 0x0800 : 0x1000;
}

}  // namespace

BusCycle board_cycle(BoardDecoding d, std::uint16_t offset) {
  if (offset >= board_window(d)) {
    throw std::out_of_range("board offset " + std::to_string(offset) + " is outside the " +
                            std::to_string(board_window(d)) + "-byte chip window");
  }
  const bool line = (offset & select_line(d)) != 0;
  BusCycle c;
  c.address = offset;  // the chip sees the board's address lines as A15-0
  c.mcsn0 = false;
  c.pcsn0 = false;
  c.mcsn1 = line;
  c.pcs1 = line;
  return c;
}

std::uint16_t BoardBus::read16(std::uint16_t offset) {
  return chip_.bus_word_read(board_cycle(decoding_, offset));
}

void BoardBus::write16(std::uint16_t offset, std::uint16_t value) {
  chip_.bus_word_write(board_cycle(decoding_, offset), value);
}

std::uint16_t BoardBus::ram_offset(std::uint16_t word) const {
  const std::uint32_t offset = word * 2u;
  if (offset >= select_line(decoding_)) {
    throw std::out_of_range("RAM word " + std::to_string(word) +
                            " is beyond what this board decoding reaches");
  }
  return static_cast<std::uint16_t>(offset);
}

std::uint16_t BoardBus::register_offset(std::uint16_t word) const {
  if (word > 0x3F) {
    throw std::out_of_range("register word " + std::to_string(word) + " is beyond A6-1");
  }
  return static_cast<std::uint16_t>(select_line(decoding_) + word * 2u);
}

}  // namespace sercon::chip

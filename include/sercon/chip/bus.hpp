// One access of the µP bus interface as the chip's pins see it (datasheet 3.5.4-3.5.7),
// and the pure rules that decode it: which block is selected, which data lines carry
// which half of the addressed word.
#pragma once

#include <cstdint>

namespace sercon::chip {

// Which access RDN and WRN make under BUSMODE1-0 (datasheet Table 1). Intel
// (BUSMODE0 = 0): RDN = read, WRN = write; both low is no valid cycle and the read wins.
// Motorola (BUSMODE0 = 1): RDN is the data strobe, 0-active when BUSMODE1 = 0, and WRN
// chooses read (1) or write (0).
struct BusStrobes {
  bool read = false;
  bool write = false;
};
constexpr BusStrobes decode_strobes(bool rdn, bool wrn, bool busmode0, bool busmode1) {
  if (!busmode0) return {!rdn, !wrn && rdn};
  const bool strobe = busmode1 ? rdn : !rdn;
  return {strobe && wrn, strobe && !wrn};
}

// Pin levels are `true` = high. Defaults: nothing selected, BHEN inactive.
struct BusCycle {
  bool write = false;
  std::uint16_t address = 0;  // byte address on A15-0
  std::uint16_t data = 0;     // D15-0 during a write
  bool bhen = true;           // BHEN (active low): D15-8 in use on a 16-bit bus
  bool mcsn0 = true;          // RAM is selected when MCSN0 = MCSN1 = 0
  bool mcsn1 = true;
  bool pcsn0 = true;  // registers are selected when PCSN0 = 0 and PCS1 = 1
  bool pcs1 = false;
};

enum class BusTarget : std::uint8_t { None, Ram, Registers, Both };

struct BusResult {
  BusTarget target = BusTarget::None;
  // D15-0 as the µP sees them after a read: lines the chip does not drive float and read
  // 1 through the chip's internal pull-ups (datasheet 3.3, I_IL row for D15-0).
  std::uint16_t data = 0xFFFF;
  std::uint16_t driven = 0;  // data lines the chip drove (read) or sampled (write)
  bool busy = false;         // BUSYN went low: the telegram processor used the same word
};

constexpr BusTarget decode_target(const BusCycle& c) {
  const bool ram = !c.mcsn0 && !c.mcsn1;
  const bool regs = !c.pcsn0 && c.pcs1;
  return ram && regs ? BusTarget::Both
         : ram       ? BusTarget::Ram
         : regs      ? BusTarget::Registers
                     : BusTarget::None;
}

// Which data lines an access uses and which half of the addressed word each carries.
// 16-bit bus: D7-0 is in use when A0 = 0, D15-8 when BHEN = 0 (datasheet Table 1); D7-0
// carries the byte at the even address, D15-8 the one at the odd address. 8-bit bus: D7-0
// carries the byte A0 addresses; BHEN is ignored. BYTEDIR = 0: the even byte is the word's
// low half (low byte first); BYTEDIR = 1: its high half (high byte first).
struct ByteLanes {
  bool low_lane = false;                // D7-0 in use
  bool high_lane = false;               // D15-8 in use
  bool low_lane_is_word_high = false;   // D7-0 carries word bits 15-8
  bool high_lane_is_word_high = false;  // D15-8 carries word bits 15-8

  // Bits of the addressed word that the access reads or writes.
  constexpr std::uint16_t word_mask() const {
    std::uint16_t m = 0;
    if (low_lane) m |= low_lane_is_word_high ? 0xFF00 : 0x00FF;
    if (high_lane) m |= high_lane_is_word_high ? 0xFF00 : 0x00FF;
    return m;
  }
  // D15-0 lines in use.
  constexpr std::uint16_t data_mask() const {
    return static_cast<std::uint16_t>((low_lane ? 0x00FF : 0) | (high_lane ? 0xFF00 : 0));
  }
  // The word's bits as they appear on D15-0 (bits of unused lanes are 0).
  constexpr std::uint16_t to_data(std::uint16_t word) const {
    const unsigned hi = unsigned{word} >> 8u;
    const unsigned lo = unsigned{word} & 0xFFu;
    unsigned d = 0;
    if (low_lane) d |= low_lane_is_word_high ? hi : lo;
    if (high_lane) d |= (high_lane_is_word_high ? hi : lo) << 8u;
    return static_cast<std::uint16_t>(d);
  }
  // D15-0 as word bits (bits outside word_mask() are 0).
  constexpr std::uint16_t to_word(std::uint16_t data) const {
    const unsigned dlo = unsigned{data} & 0xFFu;
    const unsigned dhi = unsigned{data} >> 8u;
    unsigned w = 0;
    if (low_lane) w |= low_lane_is_word_high ? dlo << 8u : dlo;
    if (high_lane) w |= high_lane_is_word_high ? dhi << 8u : dhi;
    return static_cast<std::uint16_t>(w);
  }
};

constexpr ByteLanes byte_lanes(bool bus16, bool bytedir, std::uint16_t address, bool bhen) {
  const bool odd = (unsigned{address} & 1u) != 0;
  ByteLanes lanes;
  if (bus16) {
    lanes.low_lane = !odd;
    lanes.high_lane = !bhen;
    lanes.low_lane_is_word_high = bytedir;    // even byte
    lanes.high_lane_is_word_high = !bytedir;  // odd byte
  } else {
    lanes.low_lane = true;
    lanes.low_lane_is_word_high = odd != bytedir;
  }
  return lanes;
}

// Word addresses the pins reach: A6-1 for registers (0x00..0x3F), A11-1 (816) or A10-1
// (410B) for RAM; higher address lines are not connected to the block.
constexpr std::uint16_t register_word(std::uint16_t address) {
  return static_cast<std::uint16_t>((unsigned{address} >> 1u) & 0x3Fu);
}
constexpr std::uint16_t ram_word(std::uint16_t address, std::uint16_t ram_words) {
  return static_cast<std::uint16_t>((unsigned{address} >> 1u) & (ram_words - 1u));
}

}  // namespace sercon::chip

// Telegrams -> SERCOS II line levels (sercos-facts §1): flag 0x7E, address, data, FCS low
// byte first, flag; bytes LSB first; a 0 stuffed after five 1s (not in flags); NRZI
// (0 = level change, 1 = same level); idle fill `0 1111111` repeated between telegrams.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <string_view>

#include "sercon/wire/line_bits.hpp"
#include "sercon/wire/telegram.hpp"

namespace sercon::wire {

// Line-bit positions of one frame: [start_bit, end_bit) runs from the first bit of the
// opening flag to one past the last bit of the closing flag. A decoder reports the same
// positions for it.
struct EncodedFrame {
  std::size_t start_bit = 0;
  std::size_t end_bit = 0;
  friend bool operator==(const EncodedFrame&, const EncodedFrame&) = default;
};

// What encode_telegram() wrote: where the frame is, the line level after its last bit and
// the FCS it appended.
struct TelegramCoding {
  EncodedFrame frame;
  bool level_after = true;
  std::uint16_t fcs = 0;
};

// One telegram into `out` from its first bit (its bits are dropped, its storage kept), the
// line at `initial_level_high` before it: the same bits as LineEncoder(initial_level_high,
// out).telegram(address, data), without an encoder (a chip codes each telegram this way).
TelegramCoding encode_telegram(LineBits& out, bool initial_level_high, std::uint8_t address,
                               std::span<const std::uint8_t> data);

class LineEncoder {
 public:
  // The line level before the first bit this encoder writes.
  explicit LineEncoder(bool initial_level_high = true);
  // The same, writing into `buffer`'s storage from its start (its bits are dropped): a
  // buffer used before needs no allocation.
  LineEncoder(bool initial_level_high, LineBits buffer);

  // Idle fill: decoded `0` then seven `1`s, repeated, so the line changes level once every
  // 8 bits. Consecutive idle() calls continue the pattern where the last one stopped;
  // a frame restarts it, so the fill after a telegram begins with its `0`.
  void idle(std::size_t bit_count);

  // One telegram: flag, address, data, FCS (computed), flag.
  EncodedFrame telegram(std::uint8_t address, std::span<const std::uint8_t> data);
  EncodedFrame telegram(const Telegram& t) { return telegram(t.address, t.data); }

  // Error-injection helpers for tests and fuzzing.
  // A frame around `body` exactly as given (no FCS appended): flag, stuffed body, flag.
  // With a wrong FCS in the body it makes a BadFcs frame, with < 4 bytes a TooShort one.
  EncodedFrame raw_frame(std::span<const std::uint8_t> body);
  // One flag 0x7E (never stuffed); restarts the stuffing count.
  void flag();
  // Bytes LSB first with bit stuffing; the count of 1s carries on from the last call.
  void stuffed_bytes(std::span<const std::uint8_t> bytes);
  // Decoded bits straight through NRZI, no stuffing: `bits` holds '0'/'1' in line order
  // (throws std::invalid_argument on any other character). Builds aborts, misaligned
  // frames, anything. Also restarts the stuffing count.
  void raw_decoded_bits(std::string_view bits);
  // The `count` (0..64) low bits of `bits`, bit 0 first (the order bytes go on the line).
  void raw_decoded_bits(std::uint64_t bits, unsigned count);

  bool level() const { return level_; }
  // The FCS the last telegram() appended (0 before any).
  std::uint16_t fcs() const { return fcs_; }
  const LineBits& bits() const { return bits_; }
  std::size_t size() const { return bits_.size(); }
  // Hands over the line written so far; the encoder continues from the same level.
  LineBits take();

 private:
  void put_decoded(std::uint64_t msb_first, unsigned count);  // NRZI onto the line
  void flush();
  void put_levels(std::uint64_t decoded_msb_first, unsigned count);  // NRZI, 1..64 bits
  void stuff(std::span<const std::uint8_t> bytes);

  LineBits bits_;
  bool level_;
  std::uint64_t pending_ = 0;  // decoded bits not yet NRZI-coded, MSB first
  unsigned pending_count_ = 0;
  unsigned ones_run_ = 0;    // consecutive 1s for the stuffing rule
  unsigned idle_phase_ = 0;  // position in the 8-bit idle pattern
  std::uint16_t fcs_ = 0;    // of the last telegram()
};

// Fill, then each telegram followed by fill: idle_bits_between bits of fill between and
// after telegrams, and max(8, idle_bits_between) before the first so that its opening
// flag is visible to a decoder that takes line bit 0 as its level reference.
LineBits encode_stream(std::span<const Telegram> telegrams, std::size_t idle_bits_between,
                       bool initial_level_high);

}  // namespace sercon::wire

// SERCOS II line levels -> telegrams (sercos-facts §1), streaming. NRZI decode (a level
// change is a 0), flag hunt, destuffing (a 0 after five 1s is dropped), FCS check.
//
// Decisions (docs/wire.md):
// - The level before line bit 0 is taken to be bit 0's own level, so bit 0 decodes as 1.
//   Decoded bit i therefore belongs to line bit i and every position is a line-bit index.
// - A flag is `0 111111 0`; its leading 0 may be the trailing 0 of the previous flag.
//   Every flag closes the open frame (if any) and opens a new one.
// - Fewer than 8 bits between a flag and the next flag/abort/end of input is inter-frame
//   fill (idle after a flag, back-to-back flags): no frame, no error.
// - Otherwise the frame is reported: Misaligned if its bit count is not a multiple of 8,
//   TooShort below 4 bytes (address + 1 data byte + FCS), BadFcs, or None.
// - Seven 1s inside a frame is Abort; input ending inside a frame is Truncated (finish()).
// After any error the decoder hunts for the next flag.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <span>
#include <string_view>
#include <vector>

#include "sercon/wire/line_bits.hpp"

namespace sercon::wire {

enum class FrameError : std::uint8_t {
  None,
  BadFcs,      // FCS received != FCS computed over address + data
  Abort,       // stuffing violation: seven or more 1s inside a frame
  TooShort,    // whole bytes, but fewer than 4 (address + data byte + 2 FCS bytes)
  Misaligned,  // the bits between the flags are not a whole number of bytes
  Truncated,   // the input ended inside a frame
};

std::string_view to_string(FrameError error);

struct DecodedFrame {
  std::size_t start_bit = 0;  // first line bit of the opening flag
  std::size_t end_bit = 0;    // one past the closing flag, or where the error was detected
  std::uint8_t address = 0;
  // Without address and FCS when the frame has >= 4 whole bytes and error is None or
  // BadFcs. For the other errors: every whole byte received after the address (the
  // FCS cannot be told apart), and both fcs fields are 0.
  std::vector<std::uint8_t> data;
  std::uint16_t fcs_received = 0;
  std::uint16_t fcs_computed = 0;
  FrameError error = FrameError::None;

  bool ok() const { return error == FrameError::None; }
};

class LineDecoder {
 public:
  // Called for every frame, in line order. The frame is only valid during the call (it
  // is reused); the sink must not call back into this decoder.
  using Sink = std::function<void(const DecodedFrame&)>;

  explicit LineDecoder(Sink sink);

  // Chunks may split anywhere; positions stay global across calls.
  void feed(const LineBits& bits);
  // `bit_count` levels packed as in LineBits (MSB first). Throws std::invalid_argument if
  // bit_count > 8 * packed.size().
  void feed(std::span<const std::uint8_t> packed, std::size_t bit_count);
  // Reports a frame still open (with at least 8 bits) as Truncated; then the decoder starts
  // over as if new (positions restart at 0, bit 0 is again the level reference).
  void finish();

  // Line bits consumed since construction / the last finish().
  std::size_t position() const { return pos_; }

 private:
  // The decode proper; `word_at(i)` gives the 64 levels from bit i (i a multiple of 64).
  template <class WordAt>
  void feed_levels(const WordAt& word_at, std::size_t bit_count);
  void on_flag(std::size_t pos, bool zero_emitted, bool was_in_frame);
  void on_abort(std::size_t pos);
  void close_frame(std::size_t end_bit, std::size_t frame_bits, FrameError forced);
  void open_frame(std::size_t start_bit);
  std::size_t emitted_bits() const { return nbytes_ * 8 + acc_bits_; }
  bool in_frame() const;
  // The open frame's bytes: a buffer inside the decoder, on the heap once a frame outgrows
  // it (a decoder per burst then allocates nothing for its frames' bytes).
  std::uint8_t* frame_bytes() { return heap_.empty() ? inline_.data() : heap_.data(); }
  std::size_t frame_capacity() const { return heap_.empty() ? inline_.size() : heap_.size(); }
  void grow_frame_bytes();

  Sink sink_;
  std::size_t pos_ = 0;      // line bits consumed
  bool have_level_ = false;  // false until the first bit fixes the reference level
  bool last_level_ = false;
  // Hunting / destuffing state as the tables' row offset (state * 256, see decoder.cpp).
  // Every bit fed is through the tables when feed() returns: nothing waits for more.
  unsigned row_;
  std::size_t frame_start_ = 0;
  // Open frame: frame_bytes()[0, nbytes_) plus acc_bits_ bits in acc_ (first bit at bit 0);
  // at least 8 bytes of room past nbytes_.
  std::array<std::uint8_t, 128> inline_;  // not cleared: only bytes written are read
  std::vector<std::uint8_t> heap_;
  std::size_t nbytes_ = 0;
  std::uint64_t acc_ = 0;
  unsigned acc_bits_ = 0;
  DecodedFrame frame_;  // for reports while another decoder's sink runs (see close_frame)
};

std::vector<DecodedFrame> decode_all(const LineBits& bits);

}  // namespace sercon::wire

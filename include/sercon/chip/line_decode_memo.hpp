// Decoding of telegram bursts, memoized per shared bits object: a burst repeated unchanged
// around a ring (every hop passes the same SharedBits) is decoded once however many chips
// receive it; a hop that changes bits (a bit error) makes a new object and so a new decode.
// The decodes are kept with the bits (shared_bits.hpp) and go when they go. A transmitter
// seeds the whole decode of the bits it encodes (seed_decode), so an own telegram that no
// hop changes is never run through a decoder.
// docs/serial-and-ring.md, "Receiver".
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>

#include "sercon/chip/shared_bits.hpp"
#include "sercon/wire/encoder.hpp"

namespace sercon::chip {

// The whole burst. The level before bit 0 is taken to be the opposite of bit 0 (a burst
// begins with the opening flag's leading 0, a level change). Lives as long as `bits`.
// Inline: asked at every hop of a lazy chain, and almost always there already.
const BurstDecode& decode_whole_burst(const SharedBits& bits);  // the memo miss
inline const BurstDecode& decode_burst(const SharedBits& bits) {
  const BurstDecodes& d = bits.decodes();
  return d.whole ? *d.whole : decode_whole_burst(bits);
}

// The burst cut after line bit `cut_bit` (< bits->size()): the line has no edges after the
// cut, so a frame open there ends as an Abort (or Truncated) within 8 bits. Lives as long
// as `bits`.
const BurstDecode& decode_burst_prefix(const SharedBits& bits, std::size_t cut_bit);

// Gives `bits`, which are exactly one telegram as wire::LineEncoder::telegram() wrote it
// (`where` its return, `fcs` the encoder's fcs()), the whole decode decode_burst would make
// of them, built from what was encoded rather than by a decoder: the same frames, field by
// field (test serial_DecodeSeed.*). Does nothing if the bits have a whole decode already or
// the frame is not the whole burst (it must start at bit 0 and end with the last bit).
void seed_decode(const SharedBits& bits, const wire::EncodedFrame& where, std::uint8_t address,
                 std::span<const std::uint8_t> data, std::uint16_t fcs);

// encode_seeded(), the transmitter's telegram coded with this decode: line_decode_seed.hpp.

// Decodes made on this thread: bursts run through a wire::LineDecoder (memo misses) and
// decodes seeded by a transmitter, one per telegram sent. A telegram that crosses a ring
// unchanged counts once either way.
std::size_t burst_decode_count();

}  // namespace sercon::chip

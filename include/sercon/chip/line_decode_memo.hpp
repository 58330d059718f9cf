// Decoding of telegram bursts, memoized per shared bits object: a burst repeated unchanged
// around a ring (every hop passes the same SharedBits) is decoded once however many chips
// receive it; a hop that changes bits (a bit error) makes a new object and so a new decode.
// The decodes are kept with the bits (shared_bits.hpp) and go when they go.
// docs/serial-and-ring.md, "Receiver".
#pragma once

#include <cstddef>

#include "sercon/chip/shared_bits.hpp"

namespace sercon::chip {

// The whole burst. The level before bit 0 is taken to be the opposite of bit 0 (a burst
// begins with the opening flag's leading 0, a level change). Lives as long as `bits`.
const BurstDecode& decode_burst(const SharedBits& bits);

// The burst cut after line bit `cut_bit` (< bits->size()): the line has no edges after the
// cut, so a frame open there ends as an Abort (or Truncated) within 8 bits. Lives as long
// as `bits`.
const BurstDecode& decode_burst_prefix(const SharedBits& bits, std::size_t cut_bit);

// Bursts actually run through a wire::LineDecoder on this thread (memo misses).
std::size_t burst_decode_count();

}  // namespace sercon::chip

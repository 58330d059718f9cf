// Decoding of telegram bursts, memoized per shared bits object: a burst repeated unchanged
// around a ring (every hop passes the same std::shared_ptr<const LineBits>) is decoded once
// however many chips receive it; a hop that changes bits (a bit error) makes a new object
// and so a new decode. The memo is per thread (simulations on different threads share
// nothing) and forgets a burst once its bits are freed. docs/serial-and-ring.md, "Receiver".
#pragma once

#include <cstddef>
#include <memory>
#include <vector>

#include "sercon/wire/decoder.hpp"
#include "sercon/wire/line_bits.hpp"

namespace sercon::chip {

// The frames a receiver finds in one burst. Bit positions count from the burst's first bit.
struct BurstDecode {
  std::vector<wire::DecodedFrame> frames;
  std::vector<std::size_t> address_end;  // per frame: one past the address byte's last bit
};

using SharedBits = std::shared_ptr<const wire::LineBits>;

// The whole burst. The level before bit 0 is taken to be the opposite of bit 0 (a burst
// begins with the opening flag's leading 0, a level change).
std::shared_ptr<const BurstDecode> decode_burst(const SharedBits& bits);

// The burst cut after line bit `cut_bit` (< bits->size()): the line has no edges after the
// cut, so a frame open there ends as an Abort (or Truncated) within 8 bits.
std::shared_ptr<const BurstDecode> decode_burst_prefix(const SharedBits& bits, std::size_t cut_bit);

// Bursts actually run through a wire::LineDecoder on this thread (memo misses).
std::size_t burst_decode_count();

}  // namespace sercon::chip

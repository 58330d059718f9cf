// Level changes (edges) of a telegram burst's line bits, for the line monitor's count of
// distorted edges. A burst's first bit is always an edge: the level before it is taken to
// be the opposite of its own (docs/serial-and-ring.md, "Bursts are self-contained").
#pragma once

#include <cstddef>

#include "sercon/wire/line_bits.hpp"

namespace sercon::chip {

// Edges at the start of line bits [0, end_bit); end_bit is clamped to bits.size().
std::size_t count_edges(const wire::LineBits& bits, std::size_t end_bit);

// Line-bit index of the n-th edge (n >= 1), or bits.size() when the bits have fewer.
std::size_t nth_edge_bit(const wire::LineBits& bits, std::size_t n);

}  // namespace sercon::chip

#include "sercon/chip/line_edges.hpp"

#include <algorithm>
#include <bit>
#include <cstdint>

namespace sercon::chip {
namespace {

// Bit k (MSB first) set where line bit first + k differs from the bit before it.
std::uint64_t edge_word(const wire::LineBits& bits, std::size_t first) {
  const std::uint64_t w = bits.word_at(first);
  const bool before = first == 0 ? !bits.level(0) : bits.level(first - 1);
  const std::uint64_t shifted = (w >> 1) | (before ? std::uint64_t{1} << 63 : 0);
  return w ^ shifted;
}

// The `count` (1..64) most significant bits.
std::uint64_t top_bits(unsigned count) {
  return count >= 64 ? ~std::uint64_t{0} : ~(~std::uint64_t{0} >> count);
}

}  // namespace

std::size_t count_edges(const wire::LineBits& bits, std::size_t end_bit) {
  end_bit = std::min(end_bit, bits.size());
  std::size_t edges = 0;
  for (std::size_t i = 0; i < end_bit; i += 64) {
    const auto count = static_cast<unsigned>(std::min<std::size_t>(64, end_bit - i));
    edges += static_cast<std::size_t>(std::popcount(edge_word(bits, i) & top_bits(count)));
  }
  return edges;
}

std::size_t nth_edge_bit(const wire::LineBits& bits, std::size_t n) {
  if (n == 0) return 0;
  for (std::size_t i = 0; i < bits.size(); i += 64) {
    const auto count = static_cast<unsigned>(std::min<std::size_t>(64, bits.size() - i));
    std::uint64_t w = edge_word(bits, i) & top_bits(count);
    const auto in_word = static_cast<std::size_t>(std::popcount(w));
    if (n > in_word) {
      n -= in_word;
      continue;
    }
    for (; n > 1; --n) w &= ~(std::uint64_t{1} << (63 - std::countl_zero(w)));
    return i + static_cast<std::size_t>(std::countl_zero(w));
  }
  return bits.size();
}

}  // namespace sercon::chip

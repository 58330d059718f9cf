#include "sercon/ring/bit_errors.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace sercon::ring {

void BitErrors::configure(double probability, std::uint64_t seed) {
  if (!(probability >= 0.0 && probability <= 1.0)) {
    throw std::invalid_argument("bit error rate " + std::to_string(probability) +
                                " is not a probability in [0, 1]");
  }
  probability_ = probability;
  log_miss_ = std::log1p(-probability);
  rng_.seed(seed);
  flipped_ = 0;
  if (enabled()) gap_ = draw_gap();
}

// Inverse transform of the geometric distribution with the engine's raw output (the
// standard distributions may differ between library implementations; this does not).
std::uint64_t BitErrors::draw_gap() {
  if (probability_ >= 1.0) return 0;
  const double u = (static_cast<double>(rng_() >> 11) + 1.0) * 0x1.0p-53;  // (0, 1]
  const double gap = std::floor(std::log(u) / log_miss_);
  if (!(gap < 1.8e19)) return std::numeric_limits<std::uint64_t>::max();
  return static_cast<std::uint64_t>(gap);
}

chip::SharedBits BitErrors::apply(const chip::SharedBits& bits) {
  const std::uint64_t n = bits->size();
  if (!enabled() || gap_ >= n) {
    if (enabled()) gap_ -= n;
    return bits;
  }
  std::vector<std::uint8_t> packed = bits->packed_copy();
  std::uint64_t pos = gap_;
  while (pos < n) {
    packed[pos / 8] = static_cast<std::uint8_t>(packed[pos / 8] ^ (0x80u >> (pos % 8)));
    ++flipped_;
    const std::uint64_t gap = draw_gap();
    constexpr std::uint64_t kMax = std::numeric_limits<std::uint64_t>::max();
    pos = gap >= kMax - pos - 1 ? kMax : pos + 1 + gap;
  }
  gap_ = pos - n;
  return chip::share_bits(
      wire::LineBits::from_packed(std::move(packed), static_cast<std::size_t>(n)));
}

}  // namespace sercon::ring

// n -> floor(n / d) for a fixed d and any 64-bit n, by a multiplication with a precomputed
// reciprocal instead of a division (Granlund and Montgomery, "Division by invariant
// integers using multiplication", 1994, fig. 4.1): about 5 cycles instead of 40. For the
// divisions asked at nearly every event or hop (MCLK edges, the repeater's SCLK grid,
// sample times of a capture), where a 64-bit division costs more time than the rest.
#pragma once

#include <bit>
#include <cstdint>

namespace sercon::sim {

class Reciprocal {
 public:
  // d == 0 is taken as 1 (no division by zero anywhere; callers check their divisors).
  explicit Reciprocal(std::uint64_t d) : d_(d) {
    if (d <= 1) return;
    __extension__ using Wide = unsigned __int128;
    // l = ceil(log2 d) >= 1; magic = floor(2^64 (2^l - d) / d) + 1 < 2^64.
    const int l = 64 - std::countl_zero(d - 1);
    const Wide two_l_minus_d = (Wide{1} << l) - d;
    magic_ = static_cast<std::uint64_t>((two_l_minus_d << 64) / d + 1);
    shift_ = l - 1;
  }

  std::uint64_t divisor() const { return d_; }
  std::uint64_t divide(std::uint64_t n) const {
    if (d_ <= 1) return n;
    __extension__ using Wide = unsigned __int128;
    const auto t = static_cast<std::uint64_t>((Wide{magic_} * n) >> 64);
    return (t + ((n - t) >> 1)) >> shift_;
  }

 private:
  std::uint64_t d_;
  std::uint64_t magic_ = 0;
  int shift_ = 0;
};

}  // namespace sercon::sim

// Seeded random bit errors on a line: each line bit is hit with probability p, independently
// (the gaps between hits are drawn from the geometric distribution, so a burst without a hit
// costs no per-bit work and is passed on as the same shared bits object). A hit flips the
// line level in a copy of the burst's bits. The same seed gives the same errors.
#pragma once

#include <cstdint>
#include <memory>
#include <random>

#include "sercon/chip/shared_bits.hpp"

namespace sercon::ring {

class BitErrors {
 public:
  // p in [0, 1] (std::invalid_argument otherwise); p = 0 switches errors off.
  void configure(double probability, std::uint64_t seed);
  bool enabled() const { return probability_ > 0.0; }
  double probability() const { return probability_; }

  // `bits` itself when no bit is hit, else a copy with the hit levels flipped.
  chip::SharedBits apply(const chip::SharedBits& bits);
  std::uint64_t flipped() const { return flipped_; }  // bits flipped so far

 private:
  std::uint64_t draw_gap();  // error-free bits before the next hit

  double probability_ = 0.0;
  double log_miss_ = 0.0;  // ln(1 - p)
  std::mt19937_64 rng_;
  std::uint64_t gap_ = 0;
  std::uint64_t flipped_ = 0;
};

}  // namespace sercon::ring

// The dual-port RAM: 2048 x 16 bits on the 816, 1024 x 16 on the 410B (delta spec 2.5).
// Power-on contents are 0 (a project decision: determinism); resets keep the contents.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

namespace sercon::chip {

class Dpram {
 public:
  explicit Dpram(std::uint16_t words) : words_(words, 0) {}

  std::uint16_t size() const { return static_cast<std::uint16_t>(words_.size()); }
  // `word` must be < size(); std::out_of_range otherwise.
  std::uint16_t read(std::uint16_t word) const { return words_.at(word); }
  // Replaces the bits under `mask` (a byte write touches one half).
  void write(std::uint16_t word, std::uint16_t value, std::uint16_t mask = 0xFFFF) {
    auto& w = words_.at(word);
    w = static_cast<std::uint16_t>((w & ~mask) | (value & mask));
  }
  std::span<const std::uint16_t> contents() const { return words_; }
  // The words themselves, size() of them, without a bounds check: for the telegram
  // processor's port (Chip::TpRamPort), which checks its words itself. Valid as long as
  // the RAM (it never resizes).
  std::uint16_t* unchecked_words() { return words_.data(); }

 private:
  std::vector<std::uint16_t> words_;
};

}  // namespace sercon::chip

// A fixed-depth word FIFO: the storage of the receive and transmit DMA FIFOs (dma_port.hpp).
// No allocation; push on a full FIFO and pop on an empty one report failure, the caller
// decides what that means (INT_DMAERR).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

namespace sercon::chip {

template <std::size_t Depth>
class WordFifo {
 public:
  static constexpr std::size_t kDepth = Depth;

  std::size_t size() const { return count_; }
  bool empty() const { return count_ == 0; }
  bool full() const { return count_ == Depth; }
  std::uint16_t front() const { return words_[head_]; }  // meaningful when !empty()

  bool push(std::uint16_t word) {
    if (full()) return false;
    words_[(head_ + count_) % Depth] = word;
    ++count_;
    return true;
  }
  bool pop(std::uint16_t& word) {
    if (empty()) return false;
    word = words_[head_];
    head_ = (head_ + 1) % Depth;
    --count_;
    return true;
  }
  void clear() {
    head_ = 0;
    count_ = 0;
  }

 private:
  std::array<std::uint16_t, Depth> words_{};
  std::size_t head_ = 0;
  std::size_t count_ = 0;
};

}  // namespace sercon::chip

// A queue of slots reused in place, contiguous in one vector: the new back is a slot the
// caller sets (it holds what a moved-away element left in it, or T{}), and taking an
// element off the front or back moves nothing; once the back reaches the vector's end, the
// few elements left move down to its start. For elements too big to move at every step,
// where a vector's erase at the front moved the rest and a queue of values built and moved
// each one: the receiver's timeline, which takes an entry in and lets one go at every
// telegram a node reads (docs/performance.md, "Ring"). The caller lets go of what an
// element holds before taking it off, and keeps a taken slot as a moved-from T would be.
#pragma once

#include <cstddef>
#include <utility>
#include <vector>

namespace sercon::sim {

template <class T>
class SlotQueue {
 public:
  SlotQueue() = default;
  SlotQueue(const SlotQueue&) = delete;  // head_ and tail_ point into slots_
  SlotQueue& operator=(const SlotQueue&) = delete;
  ~SlotQueue() = default;

  std::size_t size() const { return static_cast<std::size_t>(tail_ - head_); }
  bool empty() const { return tail_ == head_; }

  T& operator[](std::size_t i) { return head_[i]; }
  const T& operator[](std::size_t i) const { return head_[i]; }
  T& front() { return *head_; }
  const T& front() const { return *head_; }
  T& back() { return tail_[-1]; }
  const T& back() const { return tail_[-1]; }
  T* begin() { return head_; }
  T* end() { return tail_; }
  const T* begin() const { return head_; }
  const T* end() const { return tail_; }

  // The slot after the back, now the back.
  T& push_back() {
    if (tail_ == slots_.data() + slots_.size()) [[unlikely]]
      make_room();
    return *tail_++;
  }
  void pop_back() { --tail_; }
  void pop_front() {
    if (++head_ == tail_) head_ = tail_ = slots_.data();
  }

 private:
  // Rare (every few dozen elements): kept out of the callers' code. The elements move down
  // to the start, or to a vector twice the size when more than half of it is in use.
  [[gnu::noinline, gnu::cold]] void make_room() {
    const std::size_t n = size();
    if (2 * n > slots_.size() || slots_.empty()) {
      std::vector<T> bigger(slots_.empty() ? kFirstSize : 2 * slots_.size());
      for (std::size_t i = 0; i < n; ++i) bigger[i] = std::move(head_[i]);
      slots_ = std::move(bigger);
    } else {
      for (std::size_t i = 0; i < n; ++i) slots_[i] = std::move(head_[i]);
    }
    head_ = slots_.data();
    tail_ = head_ + n;
  }

  static constexpr std::size_t kFirstSize = 32;
  std::vector<T> slots_;
  T* head_ = nullptr;  // [head_, tail_) in slots_ hold the elements
  T* tail_ = nullptr;
};

}  // namespace sercon::sim

// A queue of reused slots, for a stream that passes through a few at a time: pushed by
// reuse_back() (the caller sets every field of the slot, which holds what it held last),
// let go from the front by drop_front() and all at once by drop_all(), both leaving the
// slots as they are (a held handle goes when the slot is written again). As
// CircularQueue's reuse_back()/drop_front() use, but the elements stay contiguous in one
// buffer, so the front and the back are plain pointers: a receiver's lazy bursts, asked
// at every lazy hop, where the ring's index arithmetic cost some ten instructions a hop
// (docs/serial-and-ring.md, "Lazy hops"). When the back reaches the buffer's end the
// elements are moved to its start (or the buffer grows); drop_all() starts again there.
#pragma once

#include <cstddef>
#include <utility>
#include <vector>

namespace sercon::sim {

template <class T, std::size_t kMinCapacity = 8>
class SlotQueue {
 public:
  SlotQueue() = default;
  // Pointers into the buffer: not copied or moved.
  SlotQueue(const SlotQueue&) = delete;
  SlotQueue& operator=(const SlotQueue&) = delete;

  std::size_t size() const { return static_cast<std::size_t>(last_ - first_); }
  bool empty() const { return first_ == last_; }
  T& operator[](std::size_t i) { return first_[i]; }
  const T& operator[](std::size_t i) const { return first_[i]; }
  T& front() { return *first_; }
  const T& front() const { return *first_; }
  T& back() { return last_[-1]; }
  const T& back() const { return last_[-1]; }

  // The slot after the back, counted in as it is: the caller sets all of it. May move the
  // elements: references into the queue do not outlive it.
  T& reuse_back() {
    if (last_ == end_) [[unlikely]]
      make_room();
    return *last_++;
  }
  // The back taken back at once: its slot lets go of what it holds.
  void pop_back() { *--last_ = T{}; }
  void drop_front() { ++first_; }
  void drop_all() { first_ = last_ = slots_.data(); }

 private:
  // The back is at the buffer's end: the elements are moved to its start when they fill
  // at most half of it (so they land on slots none of them is in; what those held is let
  // go, the slots they leave hold nothing), else to a buffer twice the size.
  [[gnu::noinline, gnu::cold]] void make_room() {
    const std::size_t n = size();
    T* const start = slots_.data();
    if (first_ != start && 2 * n <= slots_.size()) {
      for (std::size_t i = 0; i < n; ++i) start[i] = std::move(first_[i]);
    } else {
      std::vector<T> bigger(slots_.empty() ? kMinCapacity : 2 * slots_.size());
      for (std::size_t i = 0; i < n; ++i) bigger[i] = std::move(first_[i]);
      slots_ = std::move(bigger);
    }
    first_ = slots_.data();
    last_ = first_ + n;
    end_ = first_ + slots_.size();
  }

  std::vector<T> slots_;  // every slot a T, in use or as last left
  T* first_ = nullptr;
  T* last_ = nullptr;
  T* end_ = nullptr;
};

}  // namespace sercon::sim

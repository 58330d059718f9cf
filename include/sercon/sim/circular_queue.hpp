// A queue in a circular buffer: elements are taken off the front and put on the back (and,
// for timelines where the later word wins, dropped off the back), each in a few
// instructions, with no moving of the rest as a steady stream passes through. For the
// short timelines a telegram passes through at every hop: a repeater's, a TxD line's, a
// fibre's history (docs/performance.md, "Ring"). A slot not in use holds T{}: a taken
// element lets go of what it holds at once; except after drop_front(), which leaves the
// slot as it was until a push overwrites it (for a queue whose pushes set every field).
#pragma once

#include <cstddef>
#include <utility>
#include <vector>

namespace sercon::sim {

template <class T>
class CircularQueue {
 public:
  CircularQueue() = default;
  CircularQueue(const CircularQueue&) = default;
  CircularQueue& operator=(const CircularQueue&) = default;
  // A moved-from queue is empty, with no buffer (its counts go with the buffer).
  CircularQueue(CircularQueue&& other) noexcept { *this = std::move(other); }
  CircularQueue& operator=(CircularQueue&& other) noexcept {
    items_ = std::exchange(other.items_, {});
    head_ = std::exchange(other.head_, 0);
    size_ = std::exchange(other.size_, 0);
    mask_ = std::exchange(other.mask_, 0);
    capacity_ = std::exchange(other.capacity_, 0);
    return *this;
  }
  ~CircularQueue() = default;

  std::size_t size() const { return size_; }
  bool empty() const { return size_ == 0; }

  T& operator[](std::size_t i) { return items_[(head_ + i) & mask_]; }
  const T& operator[](std::size_t i) const { return items_[(head_ + i) & mask_]; }
  T& front() { return items_[head_]; }
  const T& front() const { return items_[head_]; }
  T& back() { return (*this)[size_ - 1]; }
  const T& back() const { return (*this)[size_ - 1]; }

  void push_back(const T& item) { emplace_back(item); }
  void push_back(T&& item) { emplace_back(std::move(item)); }
  // With no arguments: the new back is the free slot as it is (T{}, unless drop_front() left
  // it; such a queue pushes by reuse_back() and sets all of it). An argument may be an
  // element of this queue: when the buffer must grow, the value is built before it moves.
  template <class... Args>
  T& emplace_back(Args&&... args) {
    if (size_ == capacity_) [[unlikely]] {
      T value(std::forward<Args>(args)...);
      grow();
      return next_slot() = std::move(value);
    }
    T& slot = next_slot();
    if constexpr (sizeof...(Args) > 0) slot = T(std::forward<Args>(args)...);
    return slot;
  }
  void pop_back() {
    back() = T{};
    --size_;
  }
  void pop_front() {
    items_[head_] = T{};
    head_ = (head_ + 1) & mask_;
    --size_;
  }
  // For a queue whose every push sets the whole new back (reuse_back): the front goes
  // without its slot being reset, which keeps what it held until the push that reuses the
  // slot overwrites it (a held handle is let go then, not now).
  void drop_front() {
    head_ = (head_ + 1) & mask_;
    --size_;
  }
  // The slot after the back, counted in as it is (T{}, or what drop_front() left there):
  // the caller sets all of it.
  T& reuse_back() {
    if (size_ == capacity_) [[unlikely]]
      grow();
    return next_slot();
  }
  // The front stays where it is, so the pushes that follow go on round the buffer and
  // overwrite, within one turn, what drop_front() left in the slots behind it.
  void clear() {
    while (size_ > 0) pop_back();
  }
  // clear() for a queue pushed by reuse_back(): every element goes as drop_front() lets one
  // go, its slot kept as it is until the push that reuses it (the front stays where it is).
  void drop_all() { size_ = 0; }

 private:
  // The slot after the back, counted in (the buffer has room: emplace_back grows it).
  T& next_slot() {
    ++size_;
    return back();
  }
  [[gnu::noinline, gnu::cold]] void grow() {  // rare: kept out of the callers' code
    std::vector<T> bigger(items_.empty() ? 8 : 2 * items_.size());
    for (std::size_t i = 0; i < size_; ++i) bigger[i] = std::move((*this)[i]);
    items_ = std::move(bigger);
    head_ = 0;
    mask_ = items_.size() - 1;
    capacity_ = items_.size();
  }

  std::vector<T> items_;  // a power of two of slots, or none
  std::size_t head_ = 0;
  std::size_t size_ = 0;
  std::size_t mask_ = 0;
  std::size_t capacity_ = 0;  // items_.size(), kept: a vector works it out by a division
};

}  // namespace sercon::sim

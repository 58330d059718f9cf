// A queue in one vector: elements are taken off the front and put on the back (and, for
// timelines where the later word wins, dropped off the back). Unlike std::deque it does not
// allocate and free a block every few elements as a steady stream passes through: the
// taken front is reclaimed by moving the rest down once it is at least half the vector.
// For the short timelines a telegram passes through at every hop (docs/performance.md).
#pragma once

#include <cstddef>
#include <utility>
#include <vector>

namespace sercon::sim {

template <class T>
class VectorQueue {
 public:
  using iterator = typename std::vector<T>::iterator;
  using const_iterator = typename std::vector<T>::const_iterator;

  std::size_t size() const { return items_.size() - head_; }
  bool empty() const { return items_.size() == head_; }

  T& operator[](std::size_t i) { return items_[head_ + i]; }
  const T& operator[](std::size_t i) const { return items_[head_ + i]; }
  T& front() { return items_[head_]; }
  const T& front() const { return items_[head_]; }
  T& back() { return items_.back(); }
  const T& back() const { return items_.back(); }

  iterator begin() { return items_.begin() + static_cast<std::ptrdiff_t>(head_); }
  iterator end() { return items_.end(); }
  const_iterator begin() const { return items_.begin() + static_cast<std::ptrdiff_t>(head_); }
  const_iterator end() const { return items_.end(); }

  void push_back(const T& item) { items_.push_back(item); }
  void push_back(T&& item) { items_.push_back(std::move(item)); }
  template <class... Args>
  T& emplace_back(Args&&... args) {
    return items_.emplace_back(std::forward<Args>(args)...);
  }
  void pop_back() {
    items_.pop_back();
    if (empty()) clear();
  }
  void pop_front() {
    items_[head_] = T{};  // let go of what it holds now, not at the next compaction
    ++head_;
    if (empty()) {
      clear();
    } else if (head_ >= kMinReclaim && 2 * head_ >= items_.size()) {
      items_.erase(items_.begin(), items_.begin() + static_cast<std::ptrdiff_t>(head_));
      head_ = 0;
    }
  }
  void clear() {
    items_.clear();
    head_ = 0;
  }

 private:
  static constexpr std::size_t kMinReclaim = 16;
  std::vector<T> items_;
  std::size_t head_ = 0;  // items_[0, head_) are taken
};

}  // namespace sercon::sim

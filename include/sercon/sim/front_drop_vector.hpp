// A vector whose front can go without moving the rest: the elements live in [first_, last_)
// of one buffer, pop_front() destroys the front in place, and the elements move to the
// buffer's start only when the back reaches its end (a couple of them every few pushes in a
// receiver's timeline, where a std::vector moved the rest each time the front went). The
// elements stay contiguous, so data()/begin()/end() are plain pointers as in a vector.
#pragma once

#include <cstddef>
#include <memory>
#include <utility>

namespace sercon::sim {

template <class T, std::size_t kMinCapacity = 8>
class FrontDropVector {
 public:
  FrontDropVector() = default;
  FrontDropVector(const FrontDropVector&) = delete;
  FrontDropVector& operator=(const FrontDropVector&) = delete;
  ~FrontDropVector() {
    std::destroy(first_, last_);
    if (buffer_ != nullptr) std::allocator<T>{}.deallocate(buffer_, capacity());
  }

  std::size_t size() const { return static_cast<std::size_t>(last_ - first_); }
  bool empty() const { return first_ == last_; }
  T* data() { return first_; }
  const T* data() const { return first_; }
  T* begin() { return first_; }
  T* end() { return last_; }
  const T* begin() const { return first_; }
  const T* end() const { return last_; }
  T& operator[](std::size_t i) { return first_[i]; }
  const T& operator[](std::size_t i) const { return first_[i]; }
  T& front() { return *first_; }
  const T& front() const { return *first_; }
  T& back() { return last_[-1]; }
  const T& back() const { return last_[-1]; }

  void pop_back() { std::destroy_at(--last_); }
  void pop_front() { std::destroy_at(first_++); }
  // Unlike std::vector's, `args` must not refer into this vector, and every push may move
  // the elements (not only one that grows it): pointers and references into it do not
  // outlive the next emplace_back().
  template <class... Args>
  T& emplace_back(Args&&... args) {
    if (last_ == end_) [[unlikely]]
      make_room();
    T* const at = std::construct_at(last_, std::forward<Args>(args)...);
    ++last_;
    return *at;
  }

 private:
  std::size_t capacity() const { return static_cast<std::size_t>(end_ - buffer_); }
  // The back is at the buffer's end: the elements move to its start when they fill at most
  // half of it, else to a buffer twice the size.
  [[gnu::noinline]] void make_room() {
    const std::size_t n = size();
    if (first_ != buffer_ && 2 * n <= capacity()) return relocate(buffer_);
    const std::size_t grown = capacity() < kMinCapacity ? kMinCapacity : 2 * capacity();
    T* const fresh = std::allocator<T>{}.allocate(grown);
    T* const old = buffer_;
    const std::size_t old_capacity = capacity();
    relocate(fresh);
    if (old != nullptr) std::allocator<T>{}.deallocate(old, old_capacity);
    buffer_ = fresh;
    end_ = fresh + grown;
  }
  // Moves the elements to `to` onwards (the start of this buffer, or a fresh one), in order:
  // towards the start, each lands where those before it have left.
  void relocate(T* to) {
    T* out = to;
    for (T* in = first_; in != last_; ++in, ++out) {
      std::construct_at(out, std::move(*in));
      std::destroy_at(in);
    }
    first_ = to;
    last_ = out;
  }

  T* buffer_ = nullptr;
  T* first_ = nullptr;
  T* last_ = nullptr;
  T* end_ = nullptr;
};

}  // namespace sercon::sim

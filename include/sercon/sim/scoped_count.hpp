// One more on a counter for as long as it lives, exceptions included: how deep a chain of
// calls is (a telegram passed on round a ring, a callback running inside the event loop).
#pragma once

namespace sercon::sim {

class ScopedCount {
 public:
  explicit ScopedCount(int& count) : count_(count) { ++count_; }
  ~ScopedCount() { --count_; }
  ScopedCount(const ScopedCount&) = delete;
  ScopedCount& operator=(const ScopedCount&) = delete;

 private:
  int& count_;
};

}  // namespace sercon::sim

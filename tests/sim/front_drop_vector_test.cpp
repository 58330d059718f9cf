// FrontDropVector (sercon/sim/front_drop_vector.hpp), the receiver's timeline: the same
// elements in the same order as a std::deque put through the same steps, and every element
// made is let go exactly once (moves at the buffer's end included).
#include "sercon/sim/front_drop_vector.hpp"

#include <gtest/gtest.h>

#include <deque>
#include <memory>
#include <random>

namespace sercon::sim {
namespace {

// Counts the elements alive through a shared count; a moved-from element holds no value.
struct Counted {
  Counted(int v, std::shared_ptr<int> alive) : value(v), count(std::move(alive)) { ++*count; }
  Counted(Counted&& other) noexcept : value(other.value), count(other.count) {
    other.value = -1;
    ++*count;
  }
  Counted(const Counted&) = delete;
  Counted& operator=(const Counted&) = delete;
  Counted& operator=(Counted&&) = delete;
  ~Counted() { --*count; }
  int value;
  std::shared_ptr<int> count;
};

TEST(FrontDropVector, KeepsTheOrderOfADequeThroughRandomSteps) {
  const auto alive = std::make_shared<int>(0);
  std::mt19937 rng(7);
  {
    FrontDropVector<Counted, 4> v;
    std::deque<int> model;
    for (int step = 0; step < 20'000; ++step) {
      const auto what = rng() % 10;
      if (what < 5 || model.empty()) {  // grows now and then (runs of pushes)
        v.emplace_back(step, alive);
        model.push_back(step);
      } else if (what < 8) {
        v.pop_front();
        model.pop_front();
      } else {
        v.pop_back();
        model.pop_back();
      }
      ASSERT_EQ(v.size(), model.size());
      ASSERT_EQ(v.empty(), model.empty());
      ASSERT_EQ(*alive, static_cast<int>(model.size()));
      for (std::size_t i = 0; i < model.size(); ++i) ASSERT_EQ(v[i].value, model[i]);
      if (!model.empty()) {
        ASSERT_EQ(v.front().value, model.front());
        ASSERT_EQ(v.back().value, model.back());
        ASSERT_EQ(v.data(), &v.front());
        ASSERT_EQ(v.end() - v.begin(), static_cast<std::ptrdiff_t>(model.size()));
      }
    }
  }
  EXPECT_EQ(*alive, 0);  // the destructor lets go of those left
}

// The receiver's steady state: one in, one out. The elements stay within the first buffer
// (moved to its start when the back reaches its end) and keep their values.
TEST(FrontDropVector, ASteadyStreamStaysInOneBuffer) {
  const auto alive = std::make_shared<int>(0);
  FrontDropVector<Counted, 8> v;
  v.emplace_back(0, alive);
  v.emplace_back(1, alive);
  const Counted* const first = v.data();
  for (int i = 2; i < 1000; ++i) {
    v.emplace_back(i, alive);
    v.pop_front();
    ASSERT_EQ(v.size(), 2u);
    ASSERT_EQ(v[0].value, i - 1);
    ASSERT_EQ(v[1].value, i);
    ASSERT_GE(v.data(), first);
    ASSERT_LT(v.data() + 1, first + 8);
  }
  EXPECT_EQ(*alive, 2);
}

}  // namespace
}  // namespace sercon::sim

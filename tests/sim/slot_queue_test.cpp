// SlotQueue (sercon/sim/slot_queue.hpp), a receiver's lazy bursts: the same elements in the
// same order as a std::deque put through the same steps (swaps to the buffer's start and
// growth included), and a slot's handle let go only when the slot is written again.
#include "sercon/sim/slot_queue.hpp"

#include <gtest/gtest.h>

#include <deque>
#include <memory>
#include <random>

namespace sercon::sim {
namespace {

TEST(SlotQueue, KeepsTheOrderOfADequeThroughRandomSteps) {
  std::mt19937 rng(11);
  SlotQueue<int, 4> q;
  std::deque<int> model;
  for (int step = 0; step < 20'000; ++step) {
    const auto what = rng() % 10;
    if (what < 5 || model.empty()) {  // runs of pushes: the back reaches the end, or it grows
      q.reuse_back() = step;
      model.push_back(step);
    } else if (what < 8) {
      q.drop_front();
      model.pop_front();
    } else if (what < 9) {
      q.pop_back();
      model.pop_back();
    } else if (rng() % 8 == 0) {
      q.drop_all();
      model.clear();
    }
    ASSERT_EQ(q.size(), model.size());
    ASSERT_EQ(q.empty(), model.empty());
    for (std::size_t i = 0; i < model.size(); ++i) ASSERT_EQ(q[i], model[i]) << step;
    if (!model.empty()) {
      ASSERT_EQ(q.front(), model.front());
      ASSERT_EQ(q.back(), model.back());
    }
  }
}

TEST(SlotQueue, ASlotLetsGoOfItsHandleWhenWrittenAgainOrPoppedBack) {
  SlotQueue<std::shared_ptr<int>, 4> q;
  const auto a = std::make_shared<int>(1);
  const auto b = std::make_shared<int>(2);
  q.reuse_back() = a;
  q.reuse_back() = b;
  q.drop_front();  // a's slot keeps it
  EXPECT_EQ(a.use_count(), 2);
  q.pop_back();  // b's slot lets go at once
  EXPECT_EQ(b.use_count(), 1);
  EXPECT_TRUE(q.empty());
  q.drop_all();  // starts again at the buffer's start: a's slot
  q.reuse_back() = b;
  EXPECT_EQ(a.use_count(), 1);
  EXPECT_EQ(*q.front(), 2);
}

TEST(SlotQueue, SwapsToTheStartWhenTheBackReachesTheEnd) {
  SlotQueue<int, 4> q;
  for (int i = 0; i < 4; ++i) q.reuse_back() = i;
  q.drop_front();
  q.drop_front();
  q.drop_front();  // one left, in the last slot
  q.reuse_back() = 4;
  ASSERT_EQ(q.size(), 2U);
  EXPECT_EQ(q.front(), 3);
  EXPECT_EQ(q.back(), 4);
  EXPECT_EQ(&q.front() + 1, &q.back());  // contiguous
}

}  // namespace
}  // namespace sercon::sim

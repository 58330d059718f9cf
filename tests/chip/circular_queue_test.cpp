// The timelines of a repeater, a TxD line and a fibre (sim/circular_queue.hpp): a queue in
// a circular buffer that keeps its order across wrap-around and growth, and lets go of a
// taken element at once (docs/serial-and-ring.md, "Bits objects are recycled": a released
// telegram's bits go back to the free list when the last timeline drops them).
#include "sercon/sim/circular_queue.hpp"

#include <gtest/gtest.h>

#include <deque>
#include <memory>
#include <random>
#include <string>

namespace sercon::sim {
namespace {

TEST(serial_CircularQueue, KeepsOrderAcrossWrapAndGrowth) {
  CircularQueue<int> q;
  std::deque<int> model;
  std::mt19937 rng(7);
  int next = 0;
  for (int step = 0; step < 20000; ++step) {
    const unsigned op = rng() % 8;
    if (op < 4 || model.empty()) {
      q.push_back(next);
      model.push_back(next++);
    } else if (op < 7) {
      q.pop_front();
      model.pop_front();
    } else {
      q.pop_back();
      model.pop_back();
    }
    ASSERT_EQ(q.size(), model.size());
    ASSERT_EQ(q.empty(), model.empty());
    if (!model.empty()) {
      ASSERT_EQ(q.front(), model.front());
      ASSERT_EQ(q.back(), model.back());
      ASSERT_EQ(q[model.size() / 2], model[model.size() / 2]);
    }
  }
}

TEST(serial_CircularQueue, ATakenElementIsLetGoAtOnce) {
  CircularQueue<std::shared_ptr<int>> q;
  const auto a = std::make_shared<int>(1);
  const auto b = std::make_shared<int>(2);
  for (int i = 0; i < 5; ++i) q.push_back(nullptr);  // the buffer wraps below
  for (int i = 0; i < 5; ++i) q.pop_front();
  q.push_back(a);
  q.push_back(b);
  q.emplace_back();
  EXPECT_EQ(q.back(), nullptr);  // a new slot without arguments is T{}
  EXPECT_EQ(a.use_count(), 2);
  q.pop_front();
  EXPECT_EQ(a.use_count(), 1);
  q.pop_back();
  q.pop_back();
  EXPECT_EQ(b.use_count(), 1);
  q.push_back(b);
  q.clear();
  EXPECT_EQ(b.use_count(), 1);
  EXPECT_TRUE(q.empty());
}

// push_back of an element of the queue itself, when the buffer is full: the value is built
// before the buffer moves (circular_queue.hpp), as VectorQueue (a std::vector) does. Before
// the fix, AddressSanitizer saw a heap-use-after-free here.
TEST(serial_CircularQueue, PushingAnElementOfItselfWhenFull) {
  const std::string long_text(100, 'x');  // outside the small-string buffer
  CircularQueue<std::string> q;
  for (int i = 0; i < 8; ++i) {  // the first buffer: 8 slots, now full
    q.push_back(long_text);
  }
  q.push_back(q.front());
  EXPECT_EQ(q.back(), long_text);
}

// The buffer's size is kept beside it (circular_queue.hpp): a queue moved from is empty and
// grows a buffer of its own again; the one moved to keeps the elements in order.
TEST(serial_CircularQueue, AMovedFromQueueIsEmptyAndUsable) {
  CircularQueue<int> q;
  for (int i = 0; i < 6; ++i) q.push_back(i);
  q.pop_front();
  CircularQueue<int> moved(std::move(q));
  EXPECT_EQ(moved.size(), 5u);
  EXPECT_EQ(moved.front(), 1);
  EXPECT_EQ(moved.back(), 5);
  EXPECT_TRUE(q.empty());  // NOLINT(bugprone-use-after-move): the state asserted here
  for (int i = 0; i < 20; ++i) q.push_back(i);
  EXPECT_EQ(q.size(), 20u);
  EXPECT_EQ(q[19], 19);
  CircularQueue<int> assigned;
  assigned = std::move(moved);
  EXPECT_EQ(assigned.back(), 5);
  EXPECT_TRUE(moved.empty());  // NOLINT(bugprone-use-after-move)
  moved.push_back(7);
  EXPECT_EQ(moved.front(), 7);
}

// drop_front() / reuse_back() (circular_queue.hpp): "the front goes without its slot being
// reset, which keeps what it held until the push that reuses the slot overwrites it (a held
// handle is let go then, not now)". A dropped element's handle stays counted by its slot
// while the queue goes round, and is let go when a wrapping reuse_back() hands that slot
// out "as it is (... what drop_front() left there)" and the caller sets it.
TEST(serial_CircularQueue, ADroppedFrontIsLetGoWhenAReusedBackOverwritesIt) {
  CircularQueue<std::shared_ptr<int>> q;
  const auto a = std::make_shared<int>(1);
  const auto b = std::make_shared<int>(2);
  q.reuse_back() = a;  // slot 0 of the first buffer (8 slots)
  q.reuse_back() = b;  // slot 1
  EXPECT_EQ(a.use_count(), 2);
  q.drop_front();
  EXPECT_EQ(q.size(), 1u);
  EXPECT_EQ(q.front(), b);
  EXPECT_EQ(a.use_count(), 2);                           // still in its slot: not let go now
  for (int i = 0; i < 6; ++i) q.reuse_back() = nullptr;  // slots 2..7: the buffer is full
  EXPECT_EQ(q.size(), 7u);
  EXPECT_EQ(a.use_count(), 2);
  std::shared_ptr<int>& slot = q.reuse_back();  // wraps to slot 0
  EXPECT_EQ(q.size(), 8u);
  EXPECT_EQ(slot, a);  // the slot as drop_front() left it
  const auto c = std::make_shared<int>(3);
  slot = c;  // the caller sets all of it: `a` is let go then
  EXPECT_EQ(a.use_count(), 1);
  EXPECT_EQ(q.front(), b);
  EXPECT_EQ(q.back(), c);
}

// reuse_back() on a full queue grows the buffer as emplace_back() does: the elements keep
// their order (also when the front is not at the buffer's start), and the new back is a
// fresh slot (T{}) for the caller to set whole.
TEST(serial_CircularQueue, ReuseBackOnAFullQueueGrowsAndKeepsTheOrder) {
  CircularQueue<std::shared_ptr<int>> q;
  for (int i = 0; i < 3; ++i) q.reuse_back() = std::make_shared<int>(-1);
  for (int i = 0; i < 3; ++i) q.drop_front();  // the front now at slot 3 of 8
  for (int i = 0; i < 8; ++i) q.reuse_back() = std::make_shared<int>(i);  // wraps; full
  ASSERT_EQ(q.size(), 8u);
  std::shared_ptr<int>& slot = q.reuse_back();
  ASSERT_EQ(q.size(), 9u);
  EXPECT_EQ(slot, nullptr);  // a new slot of the grown buffer, not an element or a dropped one
  slot = std::make_shared<int>(8);
  for (int i = 0; i < 9; ++i) {
    ASSERT_NE(q[static_cast<std::size_t>(i)], nullptr) << i;
    EXPECT_EQ(*q[static_cast<std::size_t>(i)], i) << i;
  }
  EXPECT_EQ(*q.front(), 0);
  EXPECT_EQ(*q.back(), 8);
}

// The fast pair is the same queue as pop_front() / push_back() (what drop_front leaves in a
// slot is never seen through the queue, since reuse_back's caller sets it whole): a random
// mix of both pairs against a std::deque, across wrap-around and growth.
TEST(serial_CircularQueue, DropFrontAndReuseBackKeepTheOrderOfPopAndPush) {
  CircularQueue<int> q;
  std::deque<int> model;
  std::mt19937 rng(11);
  int next = 0;
  for (int step = 0; step < 20000; ++step) {
    const unsigned op = rng() % 8;
    if (op < 3 || model.empty()) {
      q.reuse_back() = next;
      model.push_back(next++);
    } else if (op < 5) {
      q.push_back(next);
      model.push_back(next++);
    } else if (op < 7) {
      q.drop_front();
      model.pop_front();
    } else {
      q.pop_front();
      model.pop_front();
    }
    ASSERT_EQ(q.size(), model.size());
    if (model.empty()) continue;
    ASSERT_EQ(q.front(), model.front()) << step;
    ASSERT_EQ(q.back(), model.back()) << step;
    ASSERT_EQ(q[model.size() / 2], model[model.size() / 2]) << step;
    if (step % 1000 == 0) {
      for (std::size_t i = 0; i < model.size(); ++i) ASSERT_EQ(q[i], model[i]) << step;
    }
  }
}

}  // namespace
}  // namespace sercon::sim

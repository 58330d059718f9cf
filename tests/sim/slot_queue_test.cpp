// A queue of slots reused in place (sercon/sim/slot_queue.hpp), the receiver's timeline:
// order kept across taking off at both ends, moving down and growing; a new back is the
// slot as the element moved away or taken off left it.
#include "sercon/sim/slot_queue.hpp"

#include <gtest/gtest.h>

#include <deque>
#include <string>

namespace sercon::sim {
namespace {

void expect_same(const SlotQueue<std::string>& q, const std::deque<std::string>& model) {
  ASSERT_EQ(q.size(), model.size());
  ASSERT_EQ(q.empty(), model.empty());
  for (std::size_t i = 0; i < model.size(); ++i) EXPECT_EQ(q[i], model[i]);
  std::size_t i = 0;
  for (const std::string& s : q) EXPECT_EQ(s, model[i++]);
  if (!model.empty()) {
    EXPECT_EQ(q.front(), model.front());
    EXPECT_EQ(q.back(), model.back());
  }
}

// A stream through a queue of a few elements (it moves down many times) and runs that
// fill it far past its first size (it grows), against a deque.
TEST(SlotQueue, KeepsOrderAsAStreamPassesAndAsItGrows) {
  SlotQueue<std::string> q;
  std::deque<std::string> model;
  int next = 0;
  for (int round = 0; round < 300; ++round) {
    const int in = round % 50 == 0 ? 40 : 2;
    for (int k = 0; k < in; ++k) {
      q.push_back() = std::to_string(next);
      model.push_back(std::to_string(next++));
    }
    expect_same(q, model);
    if (round % 7 == 3) {  // the later word wins: the back taken off
      q.back().clear();    // let go, as the receiver does
      q.pop_back();
      model.pop_back();
    }
    while (model.size() > (round % 50 == 0 ? 30u : 1u)) {
      q.front().clear();
      q.pop_front();
      model.pop_front();
    }
    expect_same(q, model);
  }
  while (!model.empty()) {
    q.pop_front();
    model.pop_front();
  }
  expect_same(q, model);
  q.push_back() = "again";
  model.push_back("again");
  expect_same(q, model);
}

// The caller sets a new back whole: it is the slot as the last element there left it.
TEST(SlotQueue, NewBackIsTheSlotAsLeft) {
  SlotQueue<std::string> q;
  q.push_back() = "a";
  q.push_back() = "b";
  q.pop_back();  // not let go of
  EXPECT_EQ(q.push_back(), "b");
  EXPECT_EQ(q.size(), 2u);
}

}  // namespace
}  // namespace sercon::sim

// Review of the speed commits ef00e0a..00430cf ("behaviour unchanged"): cases where the
// behaviour did change.
#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "serial_bench.hpp"

namespace sercon::chip::testing {
namespace {

using sim::Time;

// Counts what it is told, raw (no SettledLine).
struct Counter final : LineListener {
  void line_condition(Time, LineCondition, Time) override { ++conditions; }
  void line_burst(const LineBurst& b) override { starts.push_back(b.start); }
  int conditions = 0;
  std::vector<Time> starts;
};

// On its first burst, connects `late` to TxD `pin` of `unit` (a listener joining from
// inside a callback of the TxD line).
struct Hook final : LineListener {
  Hook(SerialUnit& u, unsigned p, LineListener& l) : unit(u), pin(p), late(l) {}
  void line_condition(Time, LineCondition, Time) override {}
  void line_burst(const LineBurst&) override {
    if (done) return;
    done = true;
    unit.connect_txd(pin, late);
  }
  SerialUnit& unit;
  unsigned pin;
  LineListener& late;
  bool done = false;
};

// TxD2 and TxD3 follow the line (TxD1 off). The only listener, on TxD2, connects another to
// TxD3 while it is told of a burst. At d1d5dec TxdOutputs::line_burst walked the six
// outputs live, so TxD3's new listener got the burst from tell_line() and then again from the
// walk (two line_burst calls). Since e222858/16067d3 the lone follower is told alone: one.
TEST(review2_LoneFollower, AListenerJoiningInsideACallbackIsToldAsBefore) {
  SerialBench b;
  b.chip->reg_write(kSerCtrl, static_cast<std::uint16_t>((1u << 1) | (1u << 2) | kTxLight));
  Counter late;
  Hook hook(b.unit, 3, late);
  b.unit.connect_txd(2, hook);
  const Time t = b.period();
  const Time end = b.unit.send(10 * t, 0x01, std::vector<std::uint8_t>{0x11, 0x22});
  b.run_to(end + 20 * t);
  ASSERT_TRUE(hook.done);
  // d1d5dec: two calls, both for the same burst at 10 t.
  EXPECT_EQ(late.starts, (std::vector<Time>{10 * t, 10 * t}));
}

}  // namespace
}  // namespace sercon::chip::testing

#include "sercon/sim/circular_queue.hpp"
#include "sercon/sim/vector_queue.hpp"

#include <string>

namespace sercon::sim {
namespace {

// push_back / emplace_back of an element of the queue itself, when the buffer is full: the
// argument is read after grow() has moved it out and freed the old buffer (AddressSanitizer:
// heap-use-after-free; release: the new back is the moved-from value). VectorQueue, a
// std::vector underneath, copies such an argument correctly. No caller in src/ does this
// today (a latent trap for the next one: drop_announced_from + push_back of line.back()).
TEST(review2_CircularQueue, PushingAnElementOfItselfWhenFull) {
  const std::string long_text(100, 'x');  // outside the small-string buffer
  CircularQueue<std::string> q;
  VectorQueue<std::string> v;
  for (int i = 0; i < 8; ++i) {  // the first buffer: 8 slots, now full
    q.push_back(long_text);
    v.push_back(long_text);
  }
  v.push_back(v.front());
  q.push_back(q.front());
  EXPECT_EQ(v.back(), long_text);
  EXPECT_EQ(q.back(), long_text);
}

}  // namespace
}  // namespace sercon::sim

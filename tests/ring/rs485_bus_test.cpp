// The RS-485 bus (datasheet §1 and Fig. 4: "bus topologies with RS-485 signals are
// supported"). Project decisions (rs485_bus.hpp): a telegram reaches every other node after
// the bus delay, a node does not hear itself, the bus is silent (Dark) between telegrams,
// overlapping telegrams collide into a garbled burst.
#include "sercon/ring/rs485_bus.hpp"

#include <gtest/gtest.h>

#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "ring_bench.hpp"

namespace sercon::ring {
namespace {

using chip::LineCondition;
using sim::Time;
using testing::Ear;
using testing::Recorder;

const std::vector<std::uint8_t> kData = {0x0A, 0x0B, 0x0C, 0x0D, 0x0E, 0x0F};
constexpr Time kDelay = 20'000;  // 20 ns

// Three chips on one bus, transmitters on, repeaters off; a passive listener as fourth node.
struct BusBench {
  BusBench() : bus(s, kDelay), tap(s) {
    for (int i = 0; i < 3; ++i) {
      chips.push_back(std::make_unique<chip::Chip>(s, chip::ChipConfig{}));
      chip::Chip& c = *chips.back();
      c.reg_write(0x01, static_cast<std::uint16_t>(c.reg_read(0x01) & ~(1u << 3)));  // REPON 0
      c.reg_write(0x02, 0x0041);  // TxD1 on, light
      ears.push_back(std::make_unique<Ear>(c));
      bus.attach(*c.unit<chip::SerialUnit>());
    }
    bus.add_node(tap);
  }
  chip::SerialUnit& unit(int i) {
    return *chips[static_cast<std::size_t>(i)]->unit<chip::SerialUnit>();
  }
  Ear& ear(int i) { return *ears[static_cast<std::size_t>(i)]; }
  // Nodes 0 and 2 each heard one whole telegram, from address `address`, and nothing collided.
  void expect_only_heard_at_0_and_2(std::uint8_t address) {
    EXPECT_EQ(bus.collisions(), 0u);
    for (int i : {0, 2}) {
      ASSERT_EQ(ear(i).heard.size(), 1u) << i;
      EXPECT_TRUE(ear(i).heard[0].frame.ok()) << i;
      EXPECT_EQ(ear(i).heard[0].frame.address, address) << i;
    }
  }

  sim::Scheduler s;
  Rs485Bus bus;
  Recorder tap;
  std::vector<std::unique_ptr<chip::Chip>> chips;
  std::vector<std::unique_ptr<Ear>> ears;
};

// Decisions (rs485_bus.hpp): every other node hears a telegram after the bus delay, as the
// same bits; the sender does not hear itself; the bus falls silent (Dark) after it.
TEST(Rs485Bus, ATelegramReachesEveryOtherNodeAfterTheDelay) {
  BusBench b;
  const Time t = b.unit(0).bit_period();
  const Time start = 100 * t;
  const Time end = b.unit(0).send(start, 0x05, kData);
  b.s.run_until(end + 1000 * t);
  EXPECT_TRUE(b.ear(0).heard.empty());  // not itself
  for (int i : {1, 2}) {
    ASSERT_EQ(b.ear(i).heard.size(), 1u) << i;
    EXPECT_TRUE(b.ear(i).heard[0].frame.ok());
    EXPECT_EQ(b.ear(i).heard[0].start, start + kDelay);
    EXPECT_EQ(b.ear(i).heard[0].end, end + kDelay);
  }
  // The tap: the burst (shared bits) at start + delay, then silence at end + delay.
  std::vector<Recorder::Event> after;
  for (const auto& e : b.tap.events) {
    if (e.at >= start) after.push_back(e);
  }
  ASSERT_EQ(after.size(), 2u);
  EXPECT_TRUE(after[0].burst);
  EXPECT_EQ(after[0].at, start + kDelay);
  EXPECT_EQ(after[0].now, start + kDelay);
  EXPECT_FALSE(after[1].burst);
  EXPECT_EQ(after[1].condition, LineCondition::Dark);
  EXPECT_EQ(after[1].at, end + kDelay);
  EXPECT_EQ(b.bus.collisions(), 0u);
}

// Two telegrams overlapping: the third node and the tap get the first one cut (an Abort)
// and then garbage; no good frame at all. The two senders hear each other clean.
TEST(Rs485Bus, OverlappingTelegramsCollide) {
  BusBench b;
  const Time t = b.unit(0).bit_period();
  const Time a = 100 * t;
  const Time end_a = b.unit(0).send(a, 0x05, kData);
  const Time c = a + 40 * t;
  const Time end_c = b.unit(1).send(c, 0x06, kData);
  b.s.run_until(std::max(end_a, end_c) + 1000 * t);
  EXPECT_EQ(b.bus.collisions(), 1u);
  EXPECT_EQ(b.ear(2).ok_count(), 0u);
  ASSERT_FALSE(b.ear(2).heard.empty());
  EXPECT_EQ(b.ear(2).heard[0].frame.error, wire::FrameError::Abort);
  EXPECT_EQ(b.ear(2).heard[0].end, c + kDelay);
  ASSERT_EQ(b.ear(0).heard.size(), 1u);
  EXPECT_EQ(b.ear(0).heard[0].frame.address, 0x06);
  EXPECT_TRUE(b.ear(0).heard[0].frame.ok());
  ASSERT_EQ(b.ear(1).heard.size(), 1u);
  EXPECT_EQ(b.ear(1).heard[0].frame.address, 0x05);
  EXPECT_TRUE(b.ear(1).heard[0].frame.ok());
  // After the collision the bus works again.
  const Time later = b.unit(2).send(std::max(end_a, end_c) + 2000 * t, 0x07, kData);
  b.s.run_until(later + 1000 * t);
  EXPECT_EQ(b.ear(0).heard.back().frame.address, 0x07);
  EXPECT_TRUE(b.ear(0).heard.back().frame.ok());
}

// A sender whose output is switched off mid-telegram: the others hear it stop there.
TEST(Rs485Bus, ASenderSwitchedOffMidTelegramCutsIt) {
  BusBench b;
  const Time t = b.unit(0).bit_period();
  b.unit(0).send(100 * t, 0x05, kData);
  b.s.run_until(130 * t);
  b.chips[0]->reg_write(0x02, 0);
  b.s.run_until(1000 * t);
  ASSERT_EQ(b.ear(1).heard.size(), 1u);
  EXPECT_FALSE(b.ear(1).heard[0].frame.ok());
  EXPECT_EQ(b.ear(1).heard[0].end, 130 * t + kDelay);
}

// Line contract (line.hpp): bursts with bits, a change before now is refused (the message
// naming the time), a negative delay. A change announced for an earlier time than one
// before it supersedes it (the later word wins), it is no error.
TEST(Rs485Bus, RefusesBadInput) {
  sim::Scheduler s;
  EXPECT_THROW(Rs485Bus(s, -1), std::invalid_argument);
  Rs485Bus bus(s);
  Recorder r(s);
  const std::size_t n = bus.add_node(r);
  EXPECT_THROW(bus.driver(n + 1), std::out_of_range);
  EXPECT_THROW(bus.driver(n).line_burst(chip::LineBurst{0, 62'500, nullptr}),
               std::invalid_argument);
  EXPECT_THROW(bus.driver(n).line_burst(chip::LineBurst{500, 0, testing::telegram_bits(1, kData)}),
               std::invalid_argument);  // refused when announced, not when due
  bus.driver(n).line_condition(100, LineCondition::Idle, 62'500);
  EXPECT_NO_THROW(bus.driver(n).line_condition(50, LineCondition::Dark, 0));
  s.run_until(1000);
  try {
    bus.driver(n).line_condition(999, LineCondition::Dark, 0);
    ADD_FAILURE() << "a change before now was taken";
  } catch (const std::invalid_argument& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("999 ps is before now"), std::string::npos) << what;
  }
}

// attach(unit, txd_pin): a pin outside TxD1..6 is refused before anything changes; the bus
// keeps no receiver-only node from the failed call (review wt-a4).
TEST(Rs485Bus, AFailedAttachLeavesNoHalfAttachedNode) {
  sim::Scheduler s;
  Rs485Bus bus(s);
  chip::Chip a(s, chip::ChipConfig{});
  EXPECT_THROW(bus.attach(*a.unit<chip::SerialUnit>(), 7), std::out_of_range);
  EXPECT_THROW(bus.attach(*a.unit<chip::SerialUnit>(), 0), std::out_of_range);
  EXPECT_EQ(bus.node_count(), 0u) << "a refused attach left a node on the bus";
  EXPECT_EQ(bus.attach(*a.unit<chip::SerialUnit>(), 6), 0u);
  EXPECT_EQ(bus.node_count(), 1u);
}

// Docs "RS-485 bus": a node does not hear itself. The same unit (the same receiver)
// attached a second time would hear its own telegram through its other node: refused with
// std::invalid_argument, the bus unchanged, and the sender still does not hear itself
// (review wt-a4).
TEST(Rs485Bus, AttachingTheSameUnitTwiceIsRefused) {
  sim::Scheduler s;
  Rs485Bus bus(s);
  std::vector<std::unique_ptr<chip::Chip>> chips;
  for (int i = 0; i < 2; ++i) {
    chips.push_back(std::make_unique<chip::Chip>(s, chip::ChipConfig{}));
    chip::Chip& c = *chips.back();
    c.reg_write(0x01, static_cast<std::uint16_t>(c.reg_read(0x01) & ~(1u << 3)));  // REPON 0
    c.reg_write(0x02, 0x0041);                                                     // TxD1 on, light
  }
  chip::SerialUnit& a = *chips[0]->unit<chip::SerialUnit>();
  Ear ear_a(*chips[0]);
  Ear ear_b(*chips[1]);
  bus.attach(a);
  bus.attach(*chips[1]->unit<chip::SerialUnit>());
  EXPECT_THROW(bus.attach(a), std::invalid_argument);
  EXPECT_THROW(bus.attach(a, 2), std::invalid_argument);
  EXPECT_THROW(bus.add_node(a.rxd()), std::invalid_argument);
  EXPECT_EQ(bus.node_count(), 2u);
  const Time t = a.bit_period();
  const Time end = a.send(100 * t, 0x05, kData);
  s.run_until(end + 1000 * t);
  EXPECT_TRUE(ear_a.heard.empty()) << "the sender heard its own telegram";
  ASSERT_EQ(ear_b.heard.size(), 1u);
  EXPECT_TRUE(ear_b.heard[0].frame.ok());
}

// The bus arbitrates drivers at the moment they drive (rs485_bus.hpp): what a transmitter
// announces goes through a SettledLine (docs "Per telegram, not per bit"), so a telegram
// announced for later and overtaken before it starts (here by a reset of its chip, which
// darkens TxD: docs "Transmitter", "A reset drops telegrams not yet sent") never reaches
// the bus: no other node hears it, no collision with the telegram that is sent.
TEST(Rs485Bus, ATelegramTakenBackBeforeItStartsNeverReachesTheBus) {
  BusBench b;
  const Time t = b.unit(0).bit_period();
  b.unit(0).send(1000 * t, 0x05, kData);  // announced now for 1000 t
  b.s.run_until(500 * t);
  b.chips[0]->software_reset();
  b.s.run_until(520 * t);
  const Time end = b.unit(1).send(1020 * t, 0x06, kData);
  b.s.run_until(end + 1000 * t);
  b.expect_only_heard_at_0_and_2(0x06);
  for (const auto& e : b.tap.events) {
    EXPECT_EQ(e.now, e.at);
    if (e.burst) {
      EXPECT_EQ(e.at, 1020 * t + kDelay);
    }
  }
}

// Docs "RS-485 bus": a node's transmitter drives the bus only while it sends a telegram (its
// driver is enabled like IDLE); datasheet Table 1 IDLE: "When transmitting own data IDLE is
// 0". A node left with REPON = 1 repeats what it hears onto its TxD while its IDLE stays
// high: the bus does not carry the repeated telegram (it would collide with the sender's,
// two bit times later). Control: REPON = 0 (review wt-a4).
TEST(Rs485Bus, ARepeatedTelegramIsNotDrivenOntoTheBusWhileIdleIsHigh) {
  for (const bool repon : {false, true}) {
    BusBench b;
    chip::Chip& c1 = *b.chips[1];
    if (repon) c1.reg_write(0x01, static_cast<std::uint16_t>(c1.reg_read(0x01) | (1u << 3)));
    const Time t = b.unit(0).bit_period();
    const Time end = b.unit(0).send(100 * t, 0x05, kData);
    bool idle_low = false;
    for (Time at = 100 * t; at < end + 10 * t; at += t / 2) {
      b.s.run_until(at);
      idle_low = idle_low || c1.pin(chip::Pin::IDLE).level() == sim::Level::Low;
    }
    b.s.run_until(end + 1000 * t);
    EXPECT_FALSE(idle_low) << "REPON " << repon;  // node 1 never sends own data
    EXPECT_EQ(b.bus.collisions(), 0u) << "REPON " << repon;
    ASSERT_EQ(b.ear(2).heard.size(), 1u) << "REPON " << repon;
    EXPECT_TRUE(b.ear(2).heard[0].frame.ok()) << "REPON " << repon << ": node 2 heard error class "
                                              << wire::to_string(b.ear(2).heard[0].frame.error);
    EXPECT_TRUE(b.ear(0).heard.empty()) << "REPON " << repon << ": the sender heard a repeat";
  }
}

// With REPON = 1 a node still drives its own telegrams: the repeater's bursts are left off
// the bus, the node's own are carried.
TEST(Rs485Bus, ANodeThatRepeatsStillDrivesItsOwnTelegrams) {
  BusBench b;
  chip::Chip& c1 = *b.chips[1];
  c1.reg_write(0x01, static_cast<std::uint16_t>(c1.reg_read(0x01) | (1u << 3)));
  const Time t = b.unit(1).bit_period();
  const Time end = b.unit(1).send(100 * t, 0x06, kData);
  b.s.run_until(end + 1000 * t);
  b.expect_only_heard_at_0_and_2(0x06);
}

}  // namespace
}  // namespace sercon::ring

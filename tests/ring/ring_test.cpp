// The ring (datasheet §1: "This ring starts and ends at the master. The slaves regenerate
// and repeat their received data or send their own telegrams"; Fig. 3; facts §2 "Ring").
// Expected times come from bit counts, periods, fibre delays and the repeater's documented
// delay (2 bit times rounded up to the SCLK grid), computed here.
#include "sercon/ring/ring.hpp"

#include <gtest/gtest.h>

#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "repeating_chip.hpp"
#include "ring_bench.hpp"
#include "sercon/chip/register_map.hpp"
#include "sercon/chip/serial_unit_receiver.hpp"

namespace sercon::ring {
namespace {

using chip::ChipConfig;
using sim::Time;
using testing::bit_period_of;
using testing::config_at_mbit;
using testing::detection;
using testing::Ear;
using testing::fibre_delay;
using testing::repeated;

// RingOptions makes every fibre 1 m long unless told otherwise.
const Time kOneMetre = fibre_delay(1.0);

const std::vector<std::uint8_t> kMst = {0x00};
const std::vector<std::uint8_t> kAt = {0x01, 0x00, 0x00, 0x00};

std::vector<std::unique_ptr<Ear>> ears(Ring& ring) {
  std::vector<std::unique_ptr<Ear>> out;
  for (std::size_t i = 0; i <= ring.slave_count(); ++i)
    out.push_back(std::make_unique<Ear>(ring.node(i)));
  return out;
}

class RoundTrip : public ::testing::TestWithParam<int> {};

// Every rate, fibres of different lengths: the master's telegram reaches slave k at the sum
// of the fibre delays and the repeater delays before it, and the master at the end of the
// ring; each receiver reports it at its detection time.
TEST_P(RoundTrip, TheMastersTelegramPassesEverySlaveAndComesBack) {
  const int mbit = GetParam();
  sim::Scheduler s;
  RingOptions o;
  o.fibre_lengths_m = {1.3, 20.0, 0.7, 55.5};
  Ring ring(s, config_at_mbit(mbit), config_at_mbit(mbit), 3, o);
  ring.switch_on_lines();
  auto heard = ears(ring);
  const Time t = bit_period_of(mbit);
  const Time mclk = ring.master().mclk_period();
  const Time start = 1000 * t;
  const Time end = ring.serial(0).send(start, 0xFF, kMst);
  const Time bits = (end - start) / t;
  Time at = start;
  std::vector<Time> arrival(ring.slave_count() + 2);
  for (std::size_t k = 0; k < ring.fibre_count(); ++k) {
    at += fibre_delay(o.fibre_lengths_m[k]);
    arrival[k + 1] = at;  // at node k + 1 (the master last)
    if (k + 1 <= ring.slave_count()) at = repeated(at, t);
  }
  s.run_until(arrival.back() + 200 * t);
  for (std::size_t node = 1; node <= ring.slave_count() + 1; ++node) {
    const auto& h = heard[node % (ring.slave_count() + 1)]->heard;
    ASSERT_EQ(h.size(), 1u) << "node " << node;
    EXPECT_TRUE(h[0].frame.ok());
    EXPECT_EQ(h[0].frame.address, 0xFF);
    EXPECT_EQ(h[0].start, arrival[node]) << "node " << node;
    EXPECT_EQ(h[0].end, arrival[node] + bits * t);
    EXPECT_EQ(h[0].detected, detection(arrival[node] + bits * t, t, mclk));
    EXPECT_EQ(h[0].now, h[0].detected);
  }
}

INSTANTIATE_TEST_SUITE_P(Rates, RoundTrip, ::testing::Values(2, 4, 8, 16),
                         [](const auto& p) { return std::to_string(p.param) + "Mbit"; });

// Facts §1 "1..254 = slaves": the largest ring builds, and one telegram goes all the way
// round, decoded once for all 255 receivers (the bits are shared by every hop).
TEST(Ring, TwoHundredFiftyFourSlavesPassATelegramAllTheWayRound) {
  sim::Scheduler s;
  Ring ring(s, ChipConfig{}, ChipConfig{}, 254);
  ASSERT_EQ(ring.slave_count(), 254u);
  ASSERT_EQ(ring.fibre_count(), 255u);
  ring.switch_on_lines();
  auto heard = ears(ring);
  const Time t = ring.serial(0).bit_period();
  const Time start = 1000 * t;
  // The telegram is announced round the ring (and decoded) within send() (docs "Per
  // telegram, not per bit", "Announcements"): count from before it.
  const std::size_t decodes = chip::SerialUnit::decode_count();
  const Time end = ring.serial(0).send(start, 0xFF, kMst);
  Time at = start;
  for (std::size_t k = 0; k < ring.fibre_count(); ++k) {
    at += kOneMetre;
    if (k + 1 <= ring.slave_count()) at = repeated(at, t);
  }
  s.run_until(at + (end - start) + 200 * t);
  EXPECT_EQ(chip::SerialUnit::decode_count(), decodes + 1);
  for (std::size_t i = 0; i <= 254; ++i) {
    ASSERT_EQ(heard[i]->heard.size(), 1u) << i;
    EXPECT_TRUE(heard[i]->heard[0].frame.ok()) << i;
  }
  EXPECT_EQ(heard[0]->heard[0].start, at);
}

// Datasheet §1 "or send their own telegrams"; facts §2: each slave "inserts its own AT in
// its time slot". Slave 2 sends its AT after the MST has passed: slave 3 and the master hear
// MST then AT; slave 1 (upstream) hears only the MST.
TEST(Ring, ASlaveInsertsItsTelegramInItsSlot) {
  sim::Scheduler s;
  Ring ring(s, ChipConfig{}, ChipConfig{}, 3);
  ring.switch_on_lines();
  auto heard = ears(ring);
  const Time t = ring.serial(0).bit_period();
  ring.serial(0).send(1000 * t, 0xFF, kMst);
  const Time at_start = 2000 * t;
  const Time at_end = ring.serial(2).send(at_start, 0x02, kAt);
  s.run_until(at_end + 1000 * t);
  EXPECT_EQ(heard[1]->heard.size(), 1u);
  ASSERT_EQ(heard[3]->heard.size(), 2u);
  ASSERT_EQ(heard[0]->heard.size(), 2u);
  EXPECT_EQ(heard[0]->heard[1].frame.address, 0x02);
  EXPECT_TRUE(heard[0]->heard[1].frame.ok());
  const Time to_slave3 = at_start + kOneMetre;
  EXPECT_EQ(heard[3]->heard[1].start, to_slave3);
  EXPECT_EQ(heard[0]->heard[1].start, repeated(to_slave3, t) + kOneMetre);
}

// Datasheet Table 1 (TxD1: serial output with high impedance, TXOE) and delta spec 2.3.3
// (repeater): a TxD that is switched back on passes on what the line already announced
// (docs/serial-and-ring.md, "Announcements"). In a ring where every node repeats, that
// comes back round to the same TxD while it is being passed on (found by review: a
// use-after-free under ASan when the line's timeline grew during the telling).
TEST(Ring, TxdSwitchedBackOnPassesOnWhatIsAnnouncedWhenEveryNodeRepeats) {
  testing::AllRepeatRing all(1);  // a lap (10 µs) longer than the telegrams
  sim::Scheduler& s = all.s;
  Ring& ring = all.ring;
  chip::Chip& m = ring.master();
  const std::uint16_t txoe = chip::find_field("TXOE", m.variant())->mask();
  const std::uint16_t ctrl = m.reg_read(0x02);
  m.reg_write(0x02, static_cast<std::uint16_t>(ctrl & ~txoe));  // the ring open at the master
  auto heard = ears(ring);
  const Time t = bit_period_of(16);
  s.run_until(1000 * t);
  const std::vector<std::uint8_t> data = {0x55, 0x55};
  const chip::LineBurst first{s.now() + t, t, testing::telegram_bits(0x07, data)};
  const chip::LineBurst second{first.end() + 16 * t, t, testing::telegram_bits(0x08, data)};
  ring.serial(0).rxd().line_burst(first);  // into the master, repeated to its TxD
  ring.serial(0).rxd().line_burst(second);
  m.reg_write(0x02, ctrl);         // TXOE on before the first leaves: both go out
  s.run_until(s.now() + 300 * t);  // both in at the slave, before their first lap returns
  const std::vector<testing::Heard>& at_slave = heard[1]->heard;
  ASSERT_GE(at_slave.size(), 2u);
  EXPECT_EQ(at_slave[0].frame.address, 0x07);
  EXPECT_TRUE(at_slave[0].frame.ok());
  EXPECT_EQ(at_slave[0].start, repeated(first.start, t) + fibre_delay(1000.0));
  EXPECT_EQ(at_slave[1].frame.address, 0x08);
  EXPECT_EQ(at_slave[1].start, repeated(second.start, t) + fibre_delay(1000.0));
}

// Docs "Depth guard" (docs/serial-and-ring.md): in a ring where every node repeats, a
// telegram announced round it 600 receivers deep goes on from an event when it reaches the
// next RxD. When the node before that receiver changes its line meanwhile (TXLIGHT, REPON:
// datasheet Table 1, delta spec 2.3.3), what it announces supersedes the far-off lap, and
// the event finds in the receiver's timeline only what replaced it, which went on when it
// was announced. The event must do nothing then; it passed those changes on again, long
// past: the next fibre threw std::invalid_argument out of Scheduler::run_until, 3 ms after
// the ring had been opened (found by fuzz/ring_fuzz).
TEST(Ring, OpeningARingWhereEveryNodeRepeatsLeavesNoDeferredForwardBehind) {
  testing::AllRepeatRing all(1);  // a lap (10 µs) longer than the telegram
  sim::Scheduler& s = all.s;
  Ring& ring = all.ring;
  const std::uint16_t repon = chip::find_field("REPON", ring.master().variant())->mask();
  const Time t = bit_period_of(16);
  s.run_until(1000 * t);
  const chip::LineBurst lap{s.now() + t, t, testing::telegram_bits(0x07, {0x55, 0x55})};
  ring.serial(0).rxd().line_burst(lap);  // circles: announced 300 laps (3 ms) ahead at once
  // The master's receiver is the 601st of that call chain: it goes on from an event 3 ms
  // ahead. The slave before it goes dark, then sends its own idle fill.
  s.run_until(s.now() + 50 * sim::kMicrosecond);
  chip::Chip& slave = ring.slave(1);
  slave.reg_write(0x02, 0x0001);  // TxD1 driven, TXLIGHT off
  s.run_until(s.now() + 50 * sim::kMicrosecond);
  slave.reg_write(0x01, static_cast<std::uint16_t>(slave.reg_read(0x01) & ~repon));
  slave.reg_write(0x02, 0x0041);  // TXLIGHT on: the slave's own idle fill
  const Time opened = s.now();
  EXPECT_NO_THROW(s.run_until(opened + 5 * sim::kMillisecond));
  // What leaves the master from then on is the slave's idle fill, repeated.
  EXPECT_FALSE(ring.serial(0).receiver().input().is_burst);
  EXPECT_EQ(ring.serial(0).receiver().input().condition, chip::LineCondition::Idle);
}

// Decision (own telegram wins): a slave that sends while a telegram passes cuts it; the
// nodes after it get the cut telegram as an error and the slave's own one whole.
TEST(Ring, AnOwnTelegramCutsTheOnePassing) {
  sim::Scheduler s;
  Ring ring(s, ChipConfig{}, ChipConfig{}, 2);
  ring.switch_on_lines();
  auto heard = ears(ring);
  const Time t = ring.serial(0).bit_period();
  ring.serial(0).send(1000 * t, 0xFF, std::vector<std::uint8_t>(30, 0x11));
  const Time mst_at_slave1 = 1000 * t + kOneMetre;
  const Time own = ring.serial(1).next_bit_edge(repeated(mst_at_slave1, t) + 100 * t);
  ring.serial(1).send(own, 0x01, kAt);
  s.run_until(own + 2000 * t);
  ASSERT_EQ(heard[1]->heard.size(), 1u);
  EXPECT_TRUE(heard[1]->heard[0].frame.ok());  // slave 1 itself received the MST whole
  ASSERT_EQ(heard[2]->heard.size(), 2u);
  EXPECT_FALSE(heard[2]->heard[0].frame.ok());
  EXPECT_EQ(heard[2]->heard[0].end, own + kOneMetre);
  EXPECT_TRUE(heard[2]->heard[1].frame.ok());
  EXPECT_EQ(heard[2]->heard[1].frame.address, 0x01);
}

// Facts §5: FIBBR = "fibre broken / ring open". A break anywhere darkens every node after
// it (the repeaters pass the darkness on); each raises FIBBR FIBBRTIM bit times after its
// line went dark. Restored, FIBBR clears everywhere.
TEST(Ring, ABreakOpensTheRingForEveryNodeDownstream) {
  sim::Scheduler s;
  Ring ring(s, ChipConfig{}, ChipConfig{}, 3);
  ring.switch_on_lines();
  const Time t = ring.serial(0).bit_period();
  s.run_until(1000 * t);
  for (std::size_t i = 0; i <= 3; ++i) ring.node(i).reg_write(0x04, 0xFFFF);  // clear INTs
  for (std::size_t i = 0; i <= 3; ++i) EXPECT_FALSE(ring.node(i).reg_read(0x02) & (1u << 13));
  const Time cut = 2000 * t + 77;
  ring.fibre(1).break_at(cut);
  Time dark = cut;  // at slave 2
  std::vector<Time> fibbr(4);
  for (std::size_t node : {2u, 3u, 0u}) {
    fibbr[node] = dark + 255 * t;
    if (node != 0) dark = repeated(dark, t) + kOneMetre;
  }
  s.run_until(fibbr[0] + 1000 * t);
  for (std::size_t node : {2u, 3u, 0u}) {
    EXPECT_TRUE(ring.node(node).reg_read(0x02) & (1u << 13)) << node;
    EXPECT_TRUE(ring.node(node).reg_read(0x04) & (1u << 1)) << node;
  }
  EXPECT_FALSE(ring.node(1).reg_read(0x02) & (1u << 13));  // upstream of the break
  // Exactness at the master: FIBBR rises at its own darkness + 255 bit times.
  sim::Scheduler s2;
  Ring again(s2, ChipConfig{}, ChipConfig{}, 3);
  again.switch_on_lines();
  s2.run_until(1000 * t);
  again.fibre(1).break_at(cut);
  s2.run_until(fibbr[0] - 1);
  EXPECT_FALSE(again.master().reg_read(0x02) & (1u << 13));
  s2.run_until(fibbr[0]);
  EXPECT_TRUE(again.master().reg_read(0x02) & (1u << 13));
  again.fibre(1).restore();
  s2.run_until(fibbr[0] + 1000 * t);
  for (std::size_t node = 0; node <= 3; ++node) {
    EXPECT_FALSE(again.node(node).reg_read(0x02) & (1u << 13)) << node;
  }
}

// A slave set to another bit rate: RDIST (INT_RDIST) there, nothing decoded there; its
// repeater passes the signal on unchanged, so the rest of the ring still works.
TEST(Ring, ASlaveAtAnotherRateSeesDistortionAndStillRepeats) {
  sim::Scheduler s;
  Ring ring(s, ChipConfig{}, {ChipConfig{}, config_at_mbit(8), ChipConfig{}});
  ring.switch_on_lines();
  auto heard = ears(ring);
  const Time t = ring.serial(0).bit_period();
  s.run_until(1000 * t);
  ring.serial(0).send(1000 * t, 0xFF, kMst);
  s.run_until(3000 * t);
  EXPECT_TRUE(ring.slave(2).reg_read(0x02) & (1u << 12));  // RDIST
  EXPECT_TRUE(ring.slave(2).reg_read(0x04) & (1u << 0));   // INT_RDIST
  EXPECT_TRUE(heard[2]->heard.empty());
  EXPECT_EQ(heard[3]->ok_count(), 1u);
  EXPECT_EQ(heard[0]->ok_count(), 1u);
  EXPECT_FALSE(ring.master().reg_read(0x02) & (1u << 12));
}

// Facts §1: slaves have addresses 1..254, so a ring has 1..254 slaves; one fibre length per
// fibre; chip configs are checked by the chip.
TEST(Ring, RefusesImpossibleRings) {
  sim::Scheduler s;
  EXPECT_THROW(Ring(s, ChipConfig{}, ChipConfig{}, 0), std::invalid_argument);
  EXPECT_THROW(Ring(s, ChipConfig{}, ChipConfig{}, 255), std::invalid_argument);
  RingOptions o;
  o.fibre_lengths_m = {1.0, 2.0};
  EXPECT_THROW(Ring(s, ChipConfig{}, ChipConfig{}, 2, o), std::invalid_argument);
  o.fibre_lengths_m = {1.0, -2.0, 1.0};
  EXPECT_THROW(Ring(s, ChipConfig{}, ChipConfig{}, 2, o), std::invalid_argument);
  ChipConfig bad;
  bad.mclk_hz = 1'000'000;
  EXPECT_THROW(Ring(s, ChipConfig{}, bad, 2), std::invalid_argument);
  Ring ok(s, ChipConfig{}, ChipConfig{}, 2);
  EXPECT_THROW(ok.slave(0), std::out_of_range);
  EXPECT_THROW(ok.slave(3), std::out_of_range);
  EXPECT_THROW(ok.fibre(3), std::out_of_range);
  EXPECT_THROW(ok.node(3), std::out_of_range);
}

// docs "Ring": the refusal names the slave count asked for; a count above 254 was reported
// as "0 slaves" (review wt-a4).
TEST(Ring, TooManySlavesIsReportedWithTheCountAskedFor) {
  sim::Scheduler s;
  try {
    Ring(s, ChipConfig{}, ChipConfig{}, 0);
    ADD_FAILURE() << "0 slaves accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("0 slaves"), std::string::npos) << e.what();
  }
  try {
    Ring(s, ChipConfig{}, ChipConfig{}, 255);
    ADD_FAILURE() << "255 slaves accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("255 slaves"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace sercon::ring

namespace sercon::ring {
namespace {

// sercon.h: "a pin callback may read and write registers, RAM and pins". OUTZ = 1 floats the
// outputs and turns the serial clocks off (datasheet Table 1); a board model whose callback
// on a floating output drives SBAUD must see the chip's whole reaction to OUTZ first. Before
// (sim/signal.hpp), the callback ran half-way through it: the serial unit took the new rate
// with its clocks already off and put idle fill of bit period 0 on the fibre, which the
// fibre refused (std::invalid_argument out of drive()).
TEST(Ring, ACallbackDrivingAPinWhileOutzFloatsTheOutputsSeesTheWholeReaction) {
  sim::Scheduler scheduler;
  Ring ring(scheduler, ChipConfig{}, ChipConfig{}, 1);
  ring.switch_on_lines();
  scheduler.run_until(5 * sim::kMicrosecond);
  chip::Chip& master = ring.master();
  bool driven = false;
  master.pin(chip::Pin::INT0).watch([&](sim::Level level) {
    if (level != sim::Level::HighZ || driven) return;
    driven = true;
    master.drive(chip::Pin::SBAUD, sim::Level::High);  // 8 Mbit/s once the clocks run
  });
  ASSERT_NO_THROW(master.drive(chip::Pin::OUTZ, sim::Level::High));
  EXPECT_TRUE(driven);
  EXPECT_EQ(master.pin(chip::Pin::TxD1).level(), sim::Level::HighZ);
  ASSERT_NO_THROW(scheduler.run_until(10 * sim::kMicrosecond));
  ASSERT_NO_THROW(master.drive(chip::Pin::OUTZ, sim::Level::Low));
  ASSERT_NO_THROW(scheduler.run_until(20 * sim::kMicrosecond));
  EXPECT_EQ(master.serial_clocks().bit_rate_hz, 8'000'000);
}

}  // namespace
}  // namespace sercon::ring

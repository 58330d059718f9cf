// The receiver: bursts decoded into the telegram processor's events at exact times
// (serial_unit.hpp: start event once the address byte is in, telegram event at the first
// MCLK edge at or after end + 5.5 bit + 3 MCLK, facts §5 t_start), RECACTN (datasheet
// Table 1: "Indicates that the serial receiver is receiving a telegram"), cuts, memoized
// decoding, and the LineListener contract (line.hpp).
#include <gtest/gtest.h>

#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "register_words.hpp"
#include "sercon/chip/line_decode_memo.hpp"
#include "serial_bench.hpp"

namespace sercon::chip {
namespace {

using sim::Level;
using sim::Time;
using testing::bit_period_of;
using testing::config_at_mbit;
using testing::kRecact;
using testing::kSerCtrl;
using testing::kSerMode;
using testing::PinEdges;
using testing::SerialBench;
using testing::telegram_bits;

struct Started {
  Time now, start;
  std::uint8_t address;
};
struct Got {
  Time now, start, end, detected;
  wire::DecodedFrame frame;
};

// Records the receiver's events. It takes the telegram processor's place as the receiver's
// client, and with it takes back the processor's ReceiveInterest: every report is made
// (docs/serial-and-ring.md, "Receiver", "Only wanted reports").
struct Events {
  explicit Events(SerialBench& b) {
    b.unit.set_interest(nullptr);
    b.unit.on_telegram_start([this, &b](Time start, std::uint8_t address) {
      started.push_back({b.scheduler.now(), start, address});
    });
    b.unit.on_telegram([this, &b](const ReceivedTelegram& t) {
      got.push_back({b.scheduler.now(), t.start, t.end, t.detected, t.frame});
    });
  }
  // One telegram whose address came in, then cut at `cut`: an Abort ending there
  // (serial_unit.hpp, end "or where the error cut it").
  void expect_one_cut_at(Time cut) const {
    ASSERT_EQ(started.size(), 1u);  // the address had come in before the cut
    ASSERT_EQ(got.size(), 1u);
    EXPECT_FALSE(got[0].frame.ok());
    EXPECT_EQ(got[0].frame.error, wire::FrameError::Abort);
    EXPECT_EQ(got[0].end, cut);
  }
  std::vector<Started> started;
  std::vector<Got> got;
};

const std::vector<std::uint8_t> kData = {0x01, 0x02, 0xFF, 0xFF, 0x7E};

// Stuffed 0s that come inside the address byte (after bits 0..6, LSB first).
int stuffed_in_address(std::uint8_t a) {
  int ones = 0, stuffed = 0;
  for (int i = 0; i < 7; ++i) {
    ones = ((a >> i) & 1) != 0 ? ones + 1 : 0;
    if (ones == 5) {
      ++stuffed;
      ones = 0;
    }
  }
  return stuffed;
}

struct RateAndMclk {
  int mbit;
  std::int64_t mclk_hz;
};

class ReceiveAt : public ::testing::TestWithParam<RateAndMclk> {};

// Facts §5: start detection delay t_start = 5.5 t_bit + 3.5 / f_MCLK on average: modelled
// as the first MCLK edge at or after end + 5.5 bit + 3 MCLK (serial_unit.hpp); the start
// event uses the same pipeline after the address byte's last bit.
TEST_P(ReceiveAt, EventsComeAtTheirExactTimes) {
  const auto [mbit, mclk] = GetParam();
  SerialBench b(config_at_mbit(mbit, mclk));
  Events ev(b);
  PinEdges recactn(b, Pin::RECACTN);
  const Time t = bit_period_of(mbit);
  const Time start = 1000 * t + 7;  // off every grid: the far end of a fibre
  for (const std::uint8_t address : {std::uint8_t{0x1F}, std::uint8_t{0x3F}, std::uint8_t{0xFF}}) {
    ev.started.clear();
    ev.got.clear();
    recactn.edges.clear();
    const Time at = start + (address == 0x1F ? 0 : address == 0x3F ? 10'000 : 20'000) * t;
    const auto bits = telegram_bits(address, kData);
    b.run_to(at);
    b.unit.rxd().line_burst(LineBurst{at, t, bits});
    const Time end = at + static_cast<Time>(bits->size()) * t;
    b.run_to(end + 100 * t);
    const Time address_in = at + (16 + stuffed_in_address(address)) * t;
    ASSERT_EQ(ev.started.size(), 1u);
    EXPECT_EQ(ev.started[0].address, address);
    EXPECT_EQ(ev.started[0].start, at);
    EXPECT_EQ(ev.started[0].now, b.detection(address_in));
    ASSERT_EQ(ev.got.size(), 1u);
    EXPECT_TRUE(ev.got[0].frame.ok());
    EXPECT_EQ(ev.got[0].frame.address, address);
    EXPECT_EQ(ev.got[0].frame.data, kData);
    EXPECT_EQ(ev.got[0].start, at);
    EXPECT_EQ(ev.got[0].end, end);
    EXPECT_EQ(ev.got[0].detected, b.detection(end));
    EXPECT_EQ(ev.got[0].now, ev.got[0].detected);
    EXPECT_EQ(ev.got[0].detected % b.chip->mclk_period(), 0);
    const std::vector<std::pair<Time, Level>> expected = {{at, Level::Low}, {end, Level::High}};
    EXPECT_EQ(recactn.edges, expected);
  }
}

INSTANTIATE_TEST_SUITE_P(serial, ReceiveAt,
                         ::testing::Values(RateAndMclk{2, 16'000'000}, RateAndMclk{4, 32'000'000},
                                           RateAndMclk{8, 40'000'000}, RateAndMclk{16, 32'000'000},
                                           RateAndMclk{16, 64'000'000},
                                           // MCLK not dividing the bit period: the start
                                           // report worked out on its own, not from the
                                           // end's (at 16 Mbit/s and 62.5 MHz a whole
                                           // number of bits is a whole number of MCLK
                                           // periods only every 32 bits).
                                           RateAndMclk{4, 25'000'000}, RateAndMclk{8, 50'000'000},
                                           RateAndMclk{16, 62'500'000}),
                         [](const auto& p) {
                           return std::to_string(p.param.mbit) + "Mbit_" +
                                  std::to_string(p.param.mclk_hz / 1'000'000) + "MHz";
                         });

// Register table RECACT: "Receiver is inside a telegram (RECACTN pin low)".
TEST(serial_Receiver, RecactBitFollowsThePin) {
  SerialBench b;
  const Time t = b.period();
  const auto bits = telegram_bits(0x05, kData);
  b.unit.rxd().line_burst(LineBurst{0, t, bits});
  b.run_to(20 * t);
  EXPECT_TRUE(b.chip->reg_read(kSerCtrl) & kRecact);
  EXPECT_EQ(b.chip->pin(Pin::RECACTN).level(), Level::Low);
  b.run_to(static_cast<Time>(bits->size()) * t);
  EXPECT_FALSE(b.chip->reg_read(kSerCtrl) & kRecact);
  EXPECT_EQ(b.chip->pin(Pin::RECACTN).level(), Level::High);
}

// Line contract: a change before burst.end() cuts the burst; the receiver reports the
// frame open at the cut as an error that ends at the cut (serial_unit.hpp, end "or where
// the error cut it"), and RECACTN goes high there.
TEST(serial_Receiver, ACutTelegramIsReportedAsAnErrorEndingAtTheCut) {
  SerialBench b;
  Events ev(b);
  const Time t = b.period();
  const auto bits = telegram_bits(0x05, kData);
  b.unit.rxd().line_burst(LineBurst{0, t, bits});
  b.run_to(40 * t + 3);
  b.unit.rxd().line_condition(40 * t + 3, LineCondition::Dark, 0);
  EXPECT_EQ(b.chip->pin(Pin::RECACTN).level(), Level::High);
  b.run_to(200 * t);
  ev.expect_one_cut_at(40 * t + 3);
  ASSERT_EQ(ev.got.size(), 1u);
  EXPECT_EQ(ev.got[0].detected, b.detection(40 * t + 3));
}

// docs/serial-and-ring.md, "Receiver" ("Cuts"; RECACTN: "A telegram cut by the next one
// keeps it low across the seam"): a new telegram that cuts the one before (the repeater
// inserting its own): the first is an error, the second decodes whole; RECACTN stays low
// across the seam.
TEST(serial_Receiver, ABurstCutByTheNextOne) {
  SerialBench b;
  Events ev(b);
  PinEdges recactn(b, Pin::RECACTN);
  const Time t = b.period();
  const auto first = telegram_bits(0x05, kData);
  const auto second = telegram_bits(0x06, kData);
  b.unit.rxd().line_burst(LineBurst{0, t, first});
  b.run_to(30 * t);
  b.unit.rxd().line_burst(LineBurst{30 * t, t, second});
  const Time end2 = 30 * t + static_cast<Time>(second->size()) * t;
  b.run_to(end2 + 100 * t);
  ASSERT_EQ(ev.got.size(), 2u);
  EXPECT_FALSE(ev.got[0].frame.ok());
  EXPECT_EQ(ev.got[0].end, 30 * t);
  EXPECT_TRUE(ev.got[1].frame.ok());
  EXPECT_EQ(ev.got[1].frame.address, 0x06);
  const std::vector<std::pair<Time, Level>> expected = {{0, Level::Low}, {end2, Level::High}};
  EXPECT_EQ(recactn.edges, expected);
}

// docs/serial-and-ring.md, "Receiver" ("Cuts": "the flag-only fragment is no frame at
// all"; the start event needs the address byte): a cut before the address byte is
// complete gives no start event and no telegram event.
TEST(serial_Receiver, ACutInTheOpeningFlagLeavesNothing) {
  SerialBench b;
  Events ev(b);
  const Time t = b.period();
  b.unit.rxd().line_burst(LineBurst{0, t, telegram_bits(0x05, kData)});
  b.run_to(6 * t);
  b.unit.rxd().line_condition(6 * t, LineCondition::Dark, 0);
  b.run_to(200 * t);
  EXPECT_TRUE(ev.started.empty());
  EXPECT_TRUE(ev.got.empty());
}

// Decision (docs/serial-and-ring.md, "Receiver", "Another bit rate"): "A burst whose bit
// period is not the receiver's is distorted: nothing is decoded, no events, RECACTN stays
// high" (RDIST: line_monitor_test).
TEST(serial_Receiver, ABurstAtAnotherRateDecodesNothing) {
  SerialBench b;  // 16 Mbit/s
  Events ev(b);
  b.unit.rxd().line_burst(LineBurst{0, bit_period_of(8), telegram_bits(0x05, kData)});
  b.run_to(sim::kMillisecond);
  EXPECT_TRUE(ev.started.empty());
  EXPECT_TRUE(ev.got.empty());
  EXPECT_EQ(b.chip->pin(Pin::RECACTN).level(), Level::High);
}

// Delta spec 2.3.1: the DPLL's clock at the chosen bit rate "is the input clock for the
// serial receiver and transmitter", and a burst at another rate than the receiver's is
// distorted (docs/serial-and-ring.md, "Another bit rate"). So a rate change while a
// telegram comes in cuts it for the receiver at the change: the frame open there ends as
// an Abort at the change, and RECACTN goes high. Before, the receiver reported it
// error-free while the line monitor counted its edges after the change as distorted and
// set RDIST for the same telegram.
TEST(serial_Receiver, ARateChangeCutsTheTelegramComingIn) {
  SerialBench b;  // 16 Mbit/s
  Events ev(b);
  PinEdges recactn(b, Pin::RECACTN);
  const Time t = b.period();
  const auto bits = telegram_bits(0x05, kData);
  b.unit.rxd().line_burst(LineBurst{0, t, bits});
  const Time change = 40 * t + 3;
  b.run_to(change);
  b.chip->drive(Pin::SBAUD, Level::High);  // 8 Mbit/s (delta spec 2.3.1 table, row 5)
  ASSERT_EQ(b.period(), bit_period_of(8));
  b.run_to(sim::kMillisecond);
  ev.expect_one_cut_at(change);
  const std::vector<std::pair<Time, Level>> expected = {{0, Level::Low}, {change, Level::High}};
  EXPECT_EQ(recactn.edges, expected);
}

// A telegram whose closing flag was in before the change stands; only the frame open at
// the change is cut.
TEST(serial_Receiver, ARateChangeAfterATelegramLeavesItWhole) {
  SerialBench b;
  Events ev(b);
  const Time t = b.period();
  const auto bits = telegram_bits(0x05, kData);
  b.unit.rxd().line_burst(LineBurst{0, t, bits});
  const Time end = static_cast<Time>(bits->size()) * t;
  b.run_to(end + t);
  b.chip->drive(Pin::SBAUD, Level::High);
  b.run_to(sim::kMillisecond);
  ASSERT_EQ(ev.got.size(), 1u);
  EXPECT_TRUE(ev.got[0].frame.ok());
  EXPECT_EQ(ev.got[0].end, end);
}

// A slave's MST whole at the old rate when the rate changes at its very end (the telegram
// stands: "Another bit rate"): its detection comes 5.5 of its own bit times after its end
// (facts §5 t_start), and the counter loads at that detection (docs/timing.md, "Cycle
// start"). The telegram processor must hand the cycle control the recognition point of that
// same telegram, not one worked out with the new rate's bit time, which lies before the
// detection and made the load "before now" (an exception out of the scheduler).
TEST(serial_Receiver, AnMstEndingAtARateChangeStartsTheSlavesCycleAtItsDetection) {
  namespace words = register_words;
  SerialBench b;
  b.chip->drive(Pin::SBAUD, Level::High);  // 8 Mbit/s (delta spec 2.3.1 table)
  const Time t = b.period();
  ASSERT_EQ(t, bit_period_of(8));
  b.chip->reg_write(words::kClockDiv, 5 << 8 | 31);  // MCLKST 5, 1 µs ticks at 32 MHz
  b.chip->reg_write(words::kTcntst, 3);
  b.chip->reg_write(words::kTscyc0, 250);
  const auto bits = telegram_bits(0xFF, {2});  // an MST of phase 2 (facts §2)
  const Time start = 10 * sim::kMicrosecond;
  b.unit.rxd().line_burst(LineBurst{start, t, bits});
  const Time end = start + static_cast<Time>(bits->size()) * t;
  b.run_to(end);
  b.chip->drive(Pin::SBAUD, Level::Low);  // 16 Mbit/s from the end of the MST
  ASSERT_EQ(b.period(), bit_period_of(16));
  ASSERT_NO_THROW(b.run_to(end + 5 * sim::kMicrosecond));
  EXPECT_TRUE(b.chip->reg_read(words::kIntStat) & words::kIntCycst);
  EXPECT_EQ(b.chip->reg_read(words::kPhase) >> 8, 2);  // PHASR from the MST
}

// line.hpp: "`at` / `burst.start` may lie in the future of the scheduler's now": the
// receiver takes such a change when its time comes.
TEST(serial_Receiver, ChangesAnnouncedForTheFutureAreTakenWhenTheyHappen) {
  SerialBench b;
  Events ev(b);
  PinEdges recactn(b, Pin::RECACTN);
  const Time t = b.period();
  const auto bits = telegram_bits(0x07, kData);
  b.unit.rxd().line_burst(LineBurst{500 * t, t, bits});
  b.run_to(499 * t);
  EXPECT_TRUE(recactn.edges.empty());
  b.run_to(2000 * t);
  ASSERT_FALSE(recactn.edges.empty());
  EXPECT_EQ(recactn.edges[0], std::make_pair(500 * t, Level::Low));
  ASSERT_EQ(ev.got.size(), 1u);
  EXPECT_EQ(ev.got[0].start, 500 * t);
}

// The text of the std::invalid_argument `f` throws ("" when it throws none).
template <class F>
std::string refusal(F&& f) {
  try {
    f();
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return {};
}

// Bad input to the line contract (line.hpp): clear exceptions, never UB. Malformed changes
// and a change before the scheduler's now are refused, the message naming the time; a
// change announced for an earlier time than one before it is no error (the later word
// wins: RefusesNothingOutOfOrderTheLaterWordWins).
TEST(serial_Receiver, RefusesMalformedChangesOrChangesBeforeNow) {
  SerialBench b;
  const Time t = b.period();
  LineListener& rxd = b.unit.rxd();
  EXPECT_THROW(rxd.line_burst(LineBurst{0, t, nullptr}), std::invalid_argument);
  EXPECT_THROW(rxd.line_burst(LineBurst{0, 0, telegram_bits(1, kData)}), std::invalid_argument);
  EXPECT_THROW(rxd.line_condition(0, LineCondition::Idle, 0), std::invalid_argument);
  EXPECT_THROW(rxd.line_condition(0, LineCondition::Dark, -1), std::invalid_argument);
  rxd.line_condition(100 * t, LineCondition::Idle, t);
  EXPECT_NO_THROW(rxd.line_condition(50 * t, LineCondition::Dark, 0));
  b.run_to(200 * t);
  const std::string past = refusal([&] { rxd.line_condition(150 * t, LineCondition::Dark, 0); });
  EXPECT_NE(past.find(std::to_string(150 * t)), std::string::npos) << past;
  EXPECT_NE(past.find("before now"), std::string::npos) << past;
  const std::string past_burst = refusal([&] {
    rxd.line_burst(LineBurst{199 * t, t, telegram_bits(1, kData)});
  });
  EXPECT_NE(past_burst.find(std::to_string(199 * t)), std::string::npos) << past_burst;
  EXPECT_NO_THROW(rxd.line_burst(LineBurst{200 * t, t, telegram_bits(1, kData)}));
}

// line.hpp "The later word wins" (docs/serial-and-ring.md, "Per telegram, not per bit"): a
// call supersedes everything announced before for its time and later, and cuts a telegram
// under way at its time. A telegram announced for 100 t is overtaken by Dark announced for
// 50 t afterwards: it never arrives. A telegram announced for 300 t is replaced by another
// announced for the same time: only the second is received. A telegram announced for
// 1000 t is cut by Dark announced (before it starts) for 1040 t + 3: an Abort ending there,
// RECACTN low only from 1000 t to the cut.
TEST(serial_Receiver, RefusesNothingOutOfOrderTheLaterWordWins) {
  SerialBench b;
  Events ev(b);
  PinEdges recactn(b, Pin::RECACTN);
  const Time t = b.period();
  LineListener& rxd = b.unit.rxd();
  rxd.line_condition(0, LineCondition::Idle, t);
  rxd.line_burst(LineBurst{100 * t, t, telegram_bits(0x01, kData)});
  rxd.line_condition(50 * t, LineCondition::Dark, 0);
  rxd.line_burst(LineBurst{300 * t, t, telegram_bits(0x02, kData)});
  rxd.line_burst(LineBurst{300 * t, t, telegram_bits(0x03, kData)});
  const Time end3 = 300 * t + static_cast<Time>(telegram_bits(0x03, kData)->size()) * t;
  b.run_to(900 * t);
  ASSERT_EQ(ev.started.size(), 1u);
  EXPECT_EQ(ev.started[0].address, 0x03);
  ASSERT_EQ(ev.got.size(), 1u);
  EXPECT_TRUE(ev.got[0].frame.ok());
  EXPECT_EQ(ev.got[0].frame.address, 0x03);
  EXPECT_EQ(ev.got[0].start, 300 * t);
  EXPECT_EQ(ev.got[0].end, end3);
  rxd.line_burst(LineBurst{1000 * t, t, telegram_bits(0x04, kData)});
  rxd.line_condition(1040 * t + 3, LineCondition::Dark, 0);
  b.run_to(2000 * t);
  ASSERT_EQ(ev.got.size(), 2u);
  EXPECT_EQ(ev.got[1].frame.error, wire::FrameError::Abort);
  EXPECT_EQ(ev.got[1].start, 1000 * t);
  EXPECT_EQ(ev.got[1].end, 1040 * t + 3);
  EXPECT_EQ(ev.got[1].detected, b.detection(1040 * t + 3));
  EXPECT_EQ(ev.got[1].now, ev.got[1].detected);
  const std::vector<std::pair<Time, Level>> expected = {{300 * t, Level::Low},
                                                        {end3, Level::High},
                                                        {1000 * t, Level::Low},
                                                        {1040 * t + 3, Level::High}};
  EXPECT_EQ(recactn.edges, expected);
}

// RECACTN is computed when read (lazy_pin.hpp; docs "IDLE and RECACTN are computed when
// read"), datasheet Table 1 RECACTN: "Indicates that the serial receiver is receiving a
// telegram". Without a watcher, level() is right at any time, also for a telegram
// announced long before it arrives and for one cut by a later announcement; RECACT (0x02)
// reads the same.
TEST(serial_Receiver, RecactnIsRightWhenReadWithoutAWatcher) {
  SerialBench b;
  const Time t = b.period();
  const auto bits = telegram_bits(0x05, kData);
  const Time start = 500 * t, end = start + static_cast<Time>(bits->size()) * t;
  b.unit.rxd().line_burst(LineBurst{start, t, bits});
  const Time cut_start = end + 300 * t;
  b.unit.rxd().line_burst(LineBurst{cut_start, t, bits});
  b.unit.rxd().line_condition(cut_start + 20 * t + 7, LineCondition::Idle, t);
  const auto expect_at = [&](Time at, Level level) {
    b.run_to(at);
    EXPECT_EQ(b.chip->pin(Pin::RECACTN).level(), level) << "at " << at;
    EXPECT_EQ((b.chip->reg_read(kSerCtrl) & kRecact) != 0, level == Level::Low) << "at " << at;
  };
  expect_at(start - 1, Level::High);
  expect_at(start, Level::Low);
  expect_at(end - 1, Level::Low);
  expect_at(end, Level::High);
  expect_at(cut_start - 1, Level::High);
  expect_at(cut_start, Level::Low);
  expect_at(cut_start + 20 * t + 6, Level::Low);
  expect_at(cut_start + 20 * t + 7, Level::High);
  expect_at(cut_start + 1000 * t, Level::High);
}

// With a watcher attached (a waveform, PinEdges here) every RECACTN edge comes as an event
// at its exact time (lazy_pin.hpp), also when the watcher arrives in the middle of a
// telegram (it hears the end, not the start it missed) and across back-to-back telegrams.
TEST(serial_Receiver, RecactnWithAWatcherHasEveryEdgeAtItsTime) {
  SerialBench b;
  const Time t = b.period();
  const auto bits = telegram_bits(0x05, kData);
  const Time len = static_cast<Time>(bits->size()) * t;
  const Time a = 100 * t + 11, c = a + len + 50 * t + 13;
  b.unit.rxd().line_burst(LineBurst{a, t, bits});
  b.unit.rxd().line_burst(LineBurst{c, t, bits});
  b.unit.rxd().line_burst(LineBurst{c + len, t, bits});  // back to back: no edge between
  b.run_to(a + 10 * t);
  PinEdges recactn(b, Pin::RECACTN);
  std::vector<Time> seen_at;
  b.chip->pin(Pin::RECACTN).watch([&](Level) { seen_at.push_back(b.scheduler.now()); });
  b.run_to(c + 3 * len);
  const std::vector<std::pair<Time, Level>> expected = {
      {a + len, Level::High}, {c, Level::Low}, {c + 2 * len, Level::High}};
  EXPECT_EQ(recactn.edges, expected);
  EXPECT_EQ(seen_at, (std::vector<Time>{a + len, c, c + 2 * len}));
}

// Decisions (docs/serial-and-ring.md, "Receiver", "Memoized decoding"; line_decode_memo.hpp):
// bits shared by every hop are decoded once; a changed copy is decoded again; memoization
// does not change what is reported.
TEST(serial_Receiver, DecodingIsMemoizedPerSharedBitsObject) {
  sim::Scheduler scheduler;
  Chip a(scheduler, ChipConfig{});
  Chip c(scheduler, ChipConfig{});
  std::vector<wire::DecodedFrame> seen_a, seen_c;
  a.unit<SerialUnit>()->set_interest(nullptr);  // every report (as in Events above)
  c.unit<SerialUnit>()->set_interest(nullptr);
  a.unit<SerialUnit>()->on_telegram([&](const ReceivedTelegram& t) { seen_a.push_back(t.frame); });
  c.unit<SerialUnit>()->on_telegram([&](const ReceivedTelegram& t) { seen_c.push_back(t.frame); });
  const Time t = a.unit<SerialUnit>()->bit_period();
  const auto bits = telegram_bits(0x09, kData);
  const std::size_t before = SerialUnit::decode_count();
  a.unit<SerialUnit>()->rxd().line_burst(LineBurst{0, t, bits});
  c.unit<SerialUnit>()->rxd().line_burst(LineBurst{0, t, bits});
  EXPECT_EQ(SerialUnit::decode_count(), before + 1);
  const auto copy = chip::share_bits(*bits);
  scheduler.run_until(1000 * t);
  a.unit<SerialUnit>()->rxd().line_burst(LineBurst{1000 * t, t, copy});
  EXPECT_EQ(SerialUnit::decode_count(), before + 2);
  scheduler.run_until(3000 * t);
  ASSERT_EQ(seen_a.size(), 2u);
  ASSERT_EQ(seen_c.size(), 1u);
  for (const auto& f : {seen_a[0], seen_a[1], seen_c[0]}) {
    EXPECT_TRUE(f.ok());
    EXPECT_EQ(f.address, 0x09);
    EXPECT_EQ(f.data, kData);
    EXPECT_EQ(f.start_bit, 0u);
    EXPECT_EQ(f.end_bit, bits->size());
  }
}

// docs/serial-and-ring.md, "Receiver" (the telegram event "comes for every frame the
// decoder reports"): several frames in one burst (e.g. back-to-back telegrams a test builds
// as one) are each reported with their own times.
TEST(serial_Receiver, EveryFrameOfABurstIsReported) {
  SerialBench b;
  Events ev(b);
  const Time t = b.period();
  wire::LineEncoder enc(true);
  const auto f1 = enc.telegram(0x11, kData);
  const auto f2 = enc.telegram(0x12, kData);
  const auto bits = chip::share_bits(enc.take());
  b.unit.rxd().line_burst(LineBurst{0, t, bits});
  b.run_to(2000 * t);
  ASSERT_EQ(ev.got.size(), 2u);
  const Time end1 = static_cast<Time>(f1.end_bit) * t;
  const Time start2 = static_cast<Time>(f2.start_bit) * t;
  const Time end2 = static_cast<Time>(f2.end_bit) * t;
  EXPECT_TRUE(ev.got[0].frame.ok());
  EXPECT_EQ(ev.got[0].frame.address, 0x11);
  EXPECT_EQ(ev.got[0].start, static_cast<Time>(f1.start_bit) * t);
  EXPECT_EQ(ev.got[0].end, end1);
  EXPECT_EQ(ev.got[0].detected, b.detection(end1));
  EXPECT_TRUE(ev.got[1].frame.ok());
  EXPECT_EQ(ev.got[1].frame.address, 0x12);
  EXPECT_EQ(ev.got[1].frame.data, kData);
  EXPECT_EQ(ev.got[1].start, start2);
  EXPECT_EQ(ev.got[1].end, end2);
  EXPECT_EQ(ev.got[1].detected, b.detection(end2));
  ASSERT_EQ(ev.started.size(), 2u);
  EXPECT_EQ(ev.started[1].start, start2);
  EXPECT_EQ(ev.started[1].address, 0x12);
}

// serial_unit.hpp, ReceivedTelegram::frame: "Valid only during the on_telegram callback",
// which is all of the callback (serial_unit_receiver.hpp: "prune() keeps [the entry whose
// report's handler runs] (and so its bits, which the frame handed to the handler lives in)
// until the handler returns"). A handler that resets the chip (SWRST, facts §5: a driver
// writes 0x0002; the reset clears what the receiver decoded) and announces a change on
// RxD (which prunes the timeline) before it reads the frame still reads its own telegram,
// also after a new telegram has taken a released bits object and its decode's storage
// (shared_bits.hpp, "Recycled"; under AddressSanitizer nothing is recycled and a read of
// a released decode is a use after free).
TEST(serial_Receiver, AnOnTelegramHandlerThatResetsAndPrunesStillReadsItsFrame) {
  SerialBench b;
  b.unit.set_interest(nullptr);  // every report, as Events does
  const Time t = b.period();
  const std::vector<std::uint8_t> other_data = {0x55, 0x66, 0x77};
  std::vector<Got> got;
  b.unit.on_telegram([&](const ReceivedTelegram& r) {
    b.chip->reg_write(kSerMode, 0x0002);                                     // SWRST
    b.unit.rxd().line_condition(b.scheduler.now(), LineCondition::Dark, 0);  // prunes
    wire::LineEncoder encoder(true);  // another telegram made now (a transmitter's seed)
    const wire::EncodedFrame where = encoder.telegram(0x22, other_data);
    const SharedBits other = share_bits(encoder.take());
    seed_decode(other, where, 0x22, other_data, encoder.fcs());
    got.push_back({b.scheduler.now(), r.start, r.end, r.detected, r.frame});
  });
  // Only the receiver's timeline holds the bits; the line idles after the telegram.
  std::size_t size = 0;
  {
    const auto bits = telegram_bits(0x05, kData);
    size = bits->size();
    b.unit.rxd().line_burst(LineBurst{0, t, bits});
  }
  const Time end = static_cast<Time>(size) * t;
  b.unit.rxd().line_condition(end, LineCondition::Idle, t);
  b.run_to(end + 100 * t);
  ASSERT_EQ(got.size(), 1u);
  EXPECT_EQ(got[0].now, b.detection(end));
  EXPECT_TRUE(got[0].frame.ok());
  EXPECT_EQ(got[0].frame.address, 0x05);
  EXPECT_EQ(got[0].frame.data, kData);
  EXPECT_EQ(got[0].frame.end_bit, size);
}

// The same for the start report (serial_unit_receiver.hpp: the entry whose report's handler
// runs is kept from prune() until the handler returns): an on_start handler that resets the
// chip (SWRST) and announces changes on RxD that prune the timeline, the telegram coming in
// cut at once. The telegram under way is not received ("Out of reset: the segment in force
// was not received (no opening flag seen)", serial_unit_receiver.cpp, release): no
// detection of it; the next telegram is reported whole, with its own data.
TEST(serial_Receiver, AnOnStartHandlerThatResetsAndPrunesLeavesTheReceiverWhole) {
  SerialBench b;
  Events ev(b);
  const Time t = b.period();
  bool reset_done = false;
  b.unit.on_telegram_start([&](Time start, std::uint8_t address) {
    ev.started.push_back({b.scheduler.now(), start, address});
    if (reset_done) return;
    reset_done = true;
    b.chip->reg_write(kSerMode, 0x0002);  // SWRST
    const Time now = b.scheduler.now();
    b.unit.rxd().line_condition(now, LineCondition::Dark, 0);      // cuts the telegram
    b.unit.rxd().line_condition(now + t, LineCondition::Idle, t);  // prunes
  });
  b.unit.rxd().line_burst(LineBurst{0, t, telegram_bits(0x05, kData)});
  const Time second = 1000 * t;
  const auto bits = telegram_bits(0x06, kData);
  b.run_to(second);
  b.unit.rxd().line_burst(LineBurst{second, t, bits});
  const Time end = second + static_cast<Time>(bits->size()) * t;
  b.run_to(end + 100 * t);
  ASSERT_EQ(ev.started.size(), 2u);
  EXPECT_EQ(ev.started[0].address, 0x05);
  EXPECT_EQ(ev.started[1].address, 0x06);
  EXPECT_EQ(ev.started[1].start, second);
  ASSERT_EQ(ev.got.size(), 1u);  // the second telegram only
  EXPECT_TRUE(ev.got[0].frame.ok());
  EXPECT_EQ(ev.got[0].frame.address, 0x06);
  EXPECT_EQ(ev.got[0].frame.data, kData);
  EXPECT_EQ(ev.got[0].start, second);
  EXPECT_EQ(ev.got[0].end, end);
  EXPECT_EQ(ev.got[0].detected, b.detection(end));
}

}  // namespace
}  // namespace sercon::chip

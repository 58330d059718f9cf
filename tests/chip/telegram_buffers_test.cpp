// Buffers, VAL, EN and reception errors (datasheet 4.2.1, 4.2.2; delta spec 2.10.1;
// docs/telegram-processing.md). A master alone on a loop: its own telegram comes back to
// its receiver 1 µs later and is taken by a receive header of its own list.
#include <gtest/gtest.h>

#include <array>

#include "sercon/chip/telegram_processor.hpp"
#include "telegram_bench.hpp"

namespace sercon::chip {
namespace {

using namespace telegram_testing;

constexpr Time kFibre = 1'000'000;
constexpr std::uint16_t kTscyc = 100;
constexpr std::uint16_t kTx = 0x040;      // transmit header, TRT 20, TLEN 2
constexpr std::uint16_t kRx = 0x050;      // receive header, TLEN 2
constexpr std::uint16_t kEnd = 0x060;     // end marker, TEND 90
constexpr std::uint16_t kTxData = 0x045;  // buffer 0; buffer 1 at 0x047
constexpr std::uint16_t kRxData = 0x057;  // buffer 0; buffer 1 at 0x059

class Loopback : public ::testing::Test {
 protected:
  Loopback() : ring(1, kFibre) {}

  // The list: transmit header `tx`, receive header `rx`, end marker.
  void start(std::uint16_t tx, std::uint16_t rx, std::uint16_t rx_time = 0) {
    t = timing_16mbit();
    Chip& m = chip();
    program_master(m, t, kTscyc, 4);
    words(m, 0x000, {kEnd, kTx});
    transmit_header(m, kTx, tx, 20, 2, kRx);
    words(m, 0x044, {0x8002, 0x1111, 0x2222, 0x3333, 0x4444});
    receive_header(m, kRx, rx, rx_time, 2, kEnd);
    words(m, 0x055, {0x8002, 0, 0, 0, 0, 0});
    end_marker(m, kEnd, 90);
    enable_transmission(m);
    ring.run_for(555'555);
    first = ceil_to(ring.scheduler.now(), t.mclk());
    start_master(m);
  }

  Chip& chip() { return ring.chip(0); }
  void run_cycles(int n) { ring.run_for(n * kTscyc * sim::kMicrosecond); }
  // The list telegrams (not MSTs) that left the chip.
  std::vector<Seen> sent() const {
    std::vector<Seen> v;
    for (const Seen& s : ring.fibres[0]->seen) {
      if (s.data.size() != 1) v.push_back(s);
    }
    return v;
  }
  Time cycle(int n) const { return static_cast<Time>(n) * kTscyc * sim::kMicrosecond; }
  // The list telegram of cycle n begins at TRT = 20 on the master's counter.
  Time tx_start(int n) const { return on_bit_grid(cycle_time(first, 20, t), t) + cycle(n); }

  Ring ring;
  Timing t;
  Time first = 0;
};

std::vector<std::uint8_t> le(std::uint16_t a, std::uint16_t b) {
  return {static_cast<std::uint8_t>(a), static_cast<std::uint8_t>(a >> 8),
          static_cast<std::uint8_t>(b), static_cast<std::uint8_t>(b >> 8)};
}

TEST_F(Loopback, SingleBufferGoesOutAndComesInEveryCycle) {
  // Datasheet 4.2.2: DMA = 0, DBUF = 0: one buffer. Facts §2: words little-endian.
  start(0x5005, 0x0805);  // send every cycle to 5; receive ACHK, address 5
  run_cycles(2);
  const auto s = sent();
  ASSERT_EQ(s.size(), 2u);
  EXPECT_EQ(s[0].start, tx_start(0));
  EXPECT_EQ(s[1].start, tx_start(1));
  EXPECT_EQ(s[0].address, 5);
  EXPECT_EQ(s[0].data, le(0x1111, 0x2222));
  EXPECT_EQ(chip().ram_read(kRxData), 0x1111);
  EXPECT_EQ(chip().ram_read(kRxData + 1), 0x2222);
  EXPECT_EQ(chip().ram_read(kRx), 0x0805 | 0x0400);  // VAL = 1: valid
}

TEST_F(Loopback, DoubleBufferSendsTheBufferValNames) {
  // Datasheet 4.2.1 VAL: "for double buffering ... data in buffer 0 (VAL = 0) or buffer 1
  // (VAL = 1) is valid".
  start(0x5205, 0x0805);
  run_cycles(1);
  chip().ram_write(kTx, 0x5605);  // VAL = 1
  run_cycles(1);
  const auto s = sent();
  ASSERT_EQ(s.size(), 2u);
  EXPECT_EQ(s[0].data, le(0x1111, 0x2222));
  EXPECT_EQ(s[1].data, le(0x3333, 0x4444));
}

TEST_F(Loopback, DoubleBufferReceiveFillsTheOtherBufferAndFlipsVal) {
  // Datasheet 4.2.1 VAL: "Modified by controller at ... end of receive telegrams"; the new
  // data goes into the buffer VAL does not name, then VAL names it.
  start(0x5005, 0x0A05);  // receive DBUF, VAL = 0 (buffer 0 valid)
  run_cycles(1);
  EXPECT_EQ(chip().ram_read(kRx) & 0x0400, 0x0400);
  EXPECT_EQ(chip().ram_read(kRxData + 2), 0x1111);  // buffer 1
  EXPECT_EQ(chip().ram_read(kRxData), 0);
  chip().ram_write(kTxData, 0xAAAA);
  run_cycles(1);
  EXPECT_EQ(chip().ram_read(kRx) & 0x0400, 0);
  EXPECT_EQ(chip().ram_read(kRxData), 0xAAAA);  // buffer 0
  EXPECT_EQ(chip().ram_read(kRxData + 2), 0x1111);
}

// Datasheet 4.2.2: a telegram's data comes from its transmit containers in turn, and each
// receive container takes LEN words from word POS of the telegram; facts §2: the words go
// little-endian on the line. Containers of more than four words, and two receive
// containers that take the telegram's words out of order.
TEST_F(Loopback, LongContainersGoOutInTurnAndAreStoredByPos) {
  t = timing_16mbit();
  Chip& m = chip();
  program_master(m, t, kTscyc, 4);
  words(m, 0x000, {kEnd, kTx});
  transmit_header(m, kTx, 0x5005, 20, 7, kRx);
  words(m, 0x044, {0x0005, 0x1111, 0x2222, 0x3333, 0x4444, 0x5555, 0x8002, 0x6666, 0x7777});
  receive_header(m, kRx, 0x0805, 0, 7, kEnd);
  // Container 1: LEN 5 from POS 2 at 0x057; container 2 (LASTDC): LEN 2 from POS 0 at 0x05E.
  words(m, 0x055, {0x0005, 2, 0, 0, 0, 0, 0, 0x8002, 0, 0, 0});
  end_marker(m, kEnd, 90);
  enable_transmission(m);
  ring.run_for(555'555);
  start_master(m);
  run_cycles(1);
  const auto s = sent();
  ASSERT_EQ(s.size(), 1u);
  std::vector<std::uint8_t> line;
  const std::array<std::uint16_t, 7> data{0x1111, 0x2222, 0x3333, 0x4444, 0x5555, 0x6666, 0x7777};
  for (std::uint16_t w : data) {
    line.push_back(static_cast<std::uint8_t>(w));
    line.push_back(static_cast<std::uint8_t>(w >> 8));
  }
  EXPECT_EQ(s[0].data, line);
  EXPECT_EQ(m.ram_read(kRx), 0x0C05);  // VAL set, no RERR
  for (std::uint16_t i = 0; i < 5; ++i) EXPECT_EQ(m.ram_read(0x057 + i), data[2 + i]) << i;
  EXPECT_EQ(m.ram_read(0x05E), 0x1111);
  EXPECT_EQ(m.ram_read(0x05F), 0x2222);
}

TEST_F(Loopback, SendOnceGoesOutOnceAndClearsEn) {
  // Facts §5: 0x4800 + address "send once"; delta spec 2.10.1: "If EN = 1, then the value
  // EN = 0 must be written to the DPR".
  start(0x4805, 0x0805);
  run_cycles(3);
  const auto s = sent();
  ASSERT_EQ(s.size(), 1u);
  EXPECT_EQ(s[0].start, tx_start(0));
  EXPECT_EQ(chip().ram_read(kTx), 0x4005);
}

TEST_F(Loopback, IdleTransmitHeaderSendsNothing) {
  start(0x4005, 0x0805);  // facts §5: 0x4000 idle
  run_cycles(2);
  EXPECT_TRUE(sent().empty());
}

TEST_F(Loopback, ValIsReadAgainAtTheStartAndOtherBitsAreNot) {
  // Delta spec 2.10.1.2: "the VAL bit is read from the telegram header at start of a
  // transmit telegram again, all other data of the telegram header (ADR, DMA, DBUF and EN)
  // will NOT be read again. If the telegram header must be written back to the DPR (Mode
  // EN=1), the last read VAL bit value is written together with the telegram header."
  start(0x4A05, 0x0805);  // send once, double buffer, VAL = 0, address 5
  // The header was read at the cycle start; the µP writes VAL = 1 and a new address before
  // the telegram's time (20 µs).
  ring.scheduler.run_until(cycle_time(first, 10, t));
  chip().ram_write(kTx, 0x4E06);
  run_cycles(1);
  const auto s = sent();
  ASSERT_EQ(s.size(), 1u);
  EXPECT_EQ(s[0].address, 5);                // ADR as read with the header
  EXPECT_EQ(s[0].data, le(0x3333, 0x4444));  // buffer 1: the VAL read at the start
  EXPECT_EQ(chip().ram_read(kTx), 0x4605);   // old header, EN = 0, the new VAL
}

TEST_F(Loopback, ReceiveValIsClearedAtTheStartAndSetAtTheEnd) {
  // Datasheet 4.2.1 VAL, single buffer: "Modified by controller at beginning and end of
  // receive telegrams": invalid while it arrives, valid once it ended well.
  start(0x5005, 0x0C05);  // receive with VAL = 1 from the start
  const Time in = tx_start(0) + kFibre;
  const Time address_in = in + 16 * t.bit;  // flag + address 0x05 (no stuffing)
  const Time reported = ceil_to(address_in + (11 * t.bit + 1) / 2 + 3 * t.mclk(), t.mclk());
  const Time end = in + static_cast<Time>(line_bits(5, le(0x1111, 0x2222))) * t.bit;
  ring.scheduler.run_until(reported - 1);
  EXPECT_EQ(chip().ram_read(kRx), 0x0C05);
  ring.scheduler.run_until(reported);
  EXPECT_EQ(chip().ram_read(kRx), 0x0805);
  ring.scheduler.run_until(detection(end, t) - 1);
  EXPECT_EQ(chip().ram_read(kRx), 0x0805);
  EXPECT_FALSE(chip().reg_read(kIntStat) & kIntRend);
  ring.scheduler.run_until(detection(end, t));
  EXPECT_EQ(chip().ram_read(kRx), 0x0C05);
  EXPECT_TRUE(chip().reg_read(kIntStat) & kIntRend);
}

TEST_F(Loopback, CorruptedTelegramSetsRerrCountsNerrAndLeavesValClear) {
  // Datasheet 4.2.1 RERR: "errored or not received (RERR = 1)"; NERR: error counter.
  start(0x5005, 0x0805);
  ring.fibres[0]->corrupt(2, 30);  // the list telegram of cycle 0 (after its MST): a data bit
  run_cycles(1);
  EXPECT_EQ(chip().ram_read(kRx), 0x0805 | 0x2000);  // RERR, VAL = 0
  EXPECT_EQ(chip().ram_read(kRx + 4), 1);
  const std::uint16_t s = chip().reg_read(kIntStat);
  EXPECT_TRUE(s & kIntRend);
  EXPECT_TRUE(s & kIntRerr);
  run_cycles(1);  // good again: RERR cleared, NERR keeps its count
  EXPECT_EQ(chip().ram_read(kRx), 0x0805 | 0x0400);
  EXPECT_EQ(chip().ram_read(kRx + 4), 1);
}

TEST_F(Loopback, CorruptedTelegramLeavesTheValidDoubleBufferAlone) {
  start(0x5005, 0x0E05);  // DBUF, VAL = 1: buffer 1 valid
  ring.fibres[0]->corrupt(2, 30);
  run_cycles(1);
  EXPECT_EQ(chip().ram_read(kRx), 0x0E05 | 0x2000);  // VAL still names buffer 1
}

TEST_F(Loopback, WrongLengthIsAnError) {
  start(0x5005, 0x0805);
  chip().ram_write(kRx + 2, 3);  // TLEN 3, the telegram brings 2 words
  run_cycles(1);
  EXPECT_EQ(chip().ram_read(kRx) & 0x2000, 0x2000);
  EXPECT_EQ(chip().ram_read(kRxData), 0x1111);  // what arrived is stored
}

TEST_F(Loopback, MissingTelegramInItsWindowSetsRerrEveryCycle) {
  // TCHK = 1 (datasheet 4.2.1: "The time of receiving is checked"): the window is TRT -/+ 2
  // µs (docs/telegram-processing.md); nothing comes, so RERR, NERR + 1 and INT_RERR in
  // every cycle, and no INT_REND.
  start(0x4005, 0x1805, 25);
  run_cycles(3);
  EXPECT_EQ(chip().ram_read(kRx), 0x1805 | 0x2000);
  EXPECT_EQ(chip().ram_read(kRx + 4), 3);
  const std::uint16_t s = chip().reg_read(kIntStat);
  EXPECT_TRUE(s & kIntRerr);
  EXPECT_FALSE(s & kIntRend);
}

TEST_F(Loopback, TelegramOutsideItsWindowIsNotTaken) {
  // The telegram comes at 21 µs; a window around 40 µs does not take it.
  start(0x5005, 0x1805, 40);
  run_cycles(2);
  EXPECT_EQ(chip().ram_read(kRx) & 0x2000, 0x2000);
  EXPECT_EQ(chip().ram_read(kRxData), 0);
}

TEST_F(Loopback, TelegramInsideItsWindowIsTaken) {
  start(0x5005, 0x1805, 21);
  run_cycles(2);
  EXPECT_EQ(chip().ram_read(kRx), 0x1805 | 0x0400);
  EXPECT_EQ(chip().ram_read(kRxData), 0x1111);
}

TEST_F(Loopback, AnotherAddressIsNotTakenWithAchk) {
  start(0x5006, 0x1805, 21);  // the telegram goes to 6, the header wants 5
  run_cycles(1);
  EXPECT_EQ(chip().ram_read(kRx) & 0x2000, 0x2000);
  EXPECT_EQ(chip().ram_read(kRxData), 0);
}

TEST_F(Loopback, WithoutAchkAnyAddressIsTakenAndStored) {
  // Datasheet 4.2.1 ACHK = 0: "independent on the received address ... The received
  // address is stored at ADR."
  start(0x5042, 0x1000, 21);
  run_cycles(1);
  EXPECT_EQ(chip().ram_read(kRx), 0x1042 | 0x0400);
}

TEST_F(Loopback, MstIsNeverAListTelegram) {
  // Facts §2: the MST is address 255 + one data byte. A receive header that takes any
  // address at any time (ACHK = 0, TCHK = 0) still waits for a list telegram while the own
  // MST comes back; VAL is as before.
  start(0x4005, 0x0400);
  words(chip(), 0x000, {kEnd, kRx});  // the list: just the receive header
  run_cycles(1);
  ring.run_for(50 * sim::kMicrosecond);              // the MST of cycle 1 is back
  EXPECT_EQ(chip().ram_read(kRx), 0x0400 | 0x2000);  // cycle 0 missed, VAL kept
  EXPECT_EQ(chip().ram_read(kRx + 4), 1);
  EXPECT_FALSE(chip().reg_read(kIntStat) & kIntRend);
}

}  // namespace
}  // namespace sercon::chip

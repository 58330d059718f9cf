// Buffers, VAL, EN and reception errors (datasheet 4.2.1, 4.2.2; delta spec 2.10.1;
// docs/telegram-processing.md). A master alone on a loop: its own telegram comes back to
// its receiver 1 µs later and is taken by a receive header of its own list.
#include <gtest/gtest.h>

#include <array>
#include <string>

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

// The receive header's VAL and the buffer it names, read now.
struct Named {
  bool val = false;
  std::uint16_t words[2] = {};
};

// Datasheet 4.2.1 VAL: "for double buffering ... data in buffer 0 (VAL = 0) or buffer 1
// (VAL = 1) is valid"; delta spec 2.10.1 / docs/telegram-processing.md §5: a double-buffered
// telegram is written into the buffer VAL does not name (VAL unchanged at the start), and
// VAL flips to it at the end. So at no moment while the next telegram arrives does VAL name
// a half-written buffer: read at every quarter bit from the telegram's first bit at the
// receiver to 2 µs after its detection, the named buffer holds the whole previous telegram
// up to the detection, and the whole new one from it on.
TEST_F(Loopback, DoubleBufferNamesAWholeTelegramWhileTheNextArrives) {
  start(0x5005, 0x0A05);  // receive DBUF, VAL = 0
  auto named = [this] {
    const std::uint16_t h = chip().ram_read(kRx);
    Named n;
    n.val = (h & 0x0400) != 0;
    const auto buffer = static_cast<std::uint16_t>(kRxData + (n.val ? 2 : 0));
    n.words[0] = chip().ram_read(buffer);
    n.words[1] = chip().ram_read(static_cast<std::uint16_t>(buffer + 1));
    return n;
  };
  const std::array<std::array<std::uint16_t, 2>, 4> data{
      {{0x1111, 0x2222}, {0xAAAA, 0xBBBB}, {0x5A5A, 0xA5A5}, {0x0F0F, 0xF0F0}}};
  for (int n = 0; n < 4; ++n) {
    const auto& sent = data[static_cast<std::size_t>(n)];
    words(chip(), kTxData, {sent[0], sent[1]});
    const Time in = tx_start(n) + kFibre;
    const Time end = in + static_cast<Time>(line_bits(5, le(sent[0], sent[1]))) * t.bit;
    const Time done = detection(end, t);
    for (Time at = in; at < done + 2 * sim::kMicrosecond; at += t.bit / 4) {
      ring.scheduler.run_until(at);
      const Named now = named();
      // Cycle n lands in buffer 1 when n is even (VAL 0 -> 1), in buffer 0 when odd.
      const bool arrived = at >= done;
      const bool val = arrived ? n % 2 == 0 : n % 2 == 1;
      EXPECT_EQ(now.val, val) << "cycle " << n << " at " << at - in << " ps";
      if (!arrived && n == 0) continue;  // nothing received yet: buffer 0 as set up (0)
      const auto& expect = data[static_cast<std::size_t>(arrived ? n : n - 1)];
      EXPECT_EQ(now.words[0], expect[0]) << "cycle " << n << " at " << at - in << " ps";
      EXPECT_EQ(now.words[1], expect[1]) << "cycle " << n << " at " << at - in << " ps";
    }
    ring.scheduler.run_until(first + cycle(n + 1) - 5 * sim::kMicrosecond);
    EXPECT_EQ(chip().ram_read(kRx) & 0x2000, 0) << n;  // no RERR
  }
}

// The same for a telegram cut off by a fibre break after the header took it (its address is
// in) — at its first data word, half-way, and in its closing flag: datasheet 4.2.1 RERR
// ("errored or not received"), NERR + 1; docs/telegram-processing.md §5: VAL (double buffer)
// "flips to the buffer just written when error-free, stays otherwise". Read at every quarter
// bit from the cut to the end of the cycle, VAL still names the buffer with the whole
// telegram before; once the fibre is back, the next telegram is taken again.
class LoopbackCut : public Loopback, public ::testing::WithParamInterface<int> {};

TEST_P(LoopbackCut, DoubleBufferKeepsNamingTheWholeTelegramBeforeACutOne) {
  start(0x5005, 0x0E05);   // receive DBUF, VAL = 1
  ring.run_for(cycle(1));  // cycle 0: 0x1111 0x2222 into buffer 0, VAL = 0
  ASSERT_EQ(chip().ram_read(kRx), 0x0A05);
  words(chip(), kTxData, {0xAAAA, 0xBBBB});
  const Time in = tx_start(1) + kFibre;
  const std::size_t bits = line_bits(5, le(0xAAAA, 0xBBBB));
  const std::size_t cut_bit = GetParam() >= 0 ? static_cast<std::size_t>(GetParam())
                                              : bits - static_cast<std::size_t>(-GetParam());
  const Time cut = in + static_cast<Time>(cut_bit) * t.bit;
  ring.scheduler.run_until(cut);
  ring.fibres[0]->break_far_end(cut);
  for (Time at = cut; at < first + cycle(2) - sim::kMicrosecond; at += t.bit / 4) {
    ring.scheduler.run_until(at);
    ASSERT_EQ(chip().ram_read(kRx) & 0x0400, 0) << "VAL, " << at - in << " ps after the start";
    ASSERT_EQ(chip().ram_read(kRxData), 0x1111) << at - in << " ps after the start";
    ASSERT_EQ(chip().ram_read(kRxData + 1), 0x2222) << at - in << " ps after the start";
    if (at == cut + 2 * sim::kMicrosecond) ring.fibres[0]->restore_far_end(at, t.bit);
  }
  EXPECT_EQ(chip().ram_read(kRx), 0x0A05 | 0x2000);  // RERR, VAL still 0
  EXPECT_EQ(chip().ram_read(kRx + 4), 1);            // NERR
  EXPECT_TRUE(chip().reg_read(kIntStat) & kIntRerr);
  // The buffer VAL does not name got the words that were released (docs §5: "the words that
  // arrived are stored all the same"; the receiver holds the last two bytes back until the
  // flag tells data from FCS): none when cut in the data, both when cut in the closing flag.
  const bool data_released = GetParam() < 0;
  EXPECT_EQ(chip().ram_read(kRxData + 2), data_released ? 0xAAAA : 0);
  EXPECT_EQ(chip().ram_read(kRxData + 3), data_released ? 0xBBBB : 0);
  words(chip(), kTxData, {0x5A5A, 0xA5A5});
  ring.run_for(cycle(1));  // cycle 2 arrives whole: into buffer 1, VAL = 1, RERR cleared
  EXPECT_EQ(chip().ram_read(kRx), 0x0E05);
  EXPECT_EQ(chip().ram_read(kRxData + 2), 0x5A5A);
  EXPECT_EQ(chip().ram_read(kRxData + 3), 0xA5A5);
  EXPECT_EQ(chip().ram_read(kRx + 4), 1);
}

// Cut at line bit 24 (flag and address in, first data byte under way), half-way, and 3 bits
// before the end (in the closing flag).
INSTANTIATE_TEST_SUITE_P(CutAt, LoopbackCut, ::testing::Values(24, 36, -3),
                         [](const ::testing::TestParamInfo<int>& p) {
                           return p.param >= 0 ? "Bit" + std::to_string(p.param)
                                               : "BitsBeforeEnd" + std::to_string(-p.param);
                         });

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

// An MST taken (and withdrawn) across a cycle start.
//
// docs/telegram-processing.md §3 "an MST serves no header", §2 "a receive header still
// waiting [at a new cycle start] is missed", "Next cycle: a new cycle start ends the old
// walk". The own MST goes out at TCYCSTART = 97 of a 100-µs cycle and comes back over the
// 1-µs loop: its address is in before the next cycle start, its detection after it. A
// receive header for address 255 (ACHK = 1, TCHK = 0) behind an every-cycle transmit header
// takes its address; at the detection it proves to be an MST. The header's cycle is over
// by then: it is missed for that cycle, and the new cycle's walk (its transmit telegram at
// TRT 20) goes on untouched.
TEST_F(Loopback, MstWithdrawnAfterTheNextCycleStartLeavesTheNewWalkAlone) {
  chip().reg_write(kTcycstart, 97);
  start(0x5005, 0x08FF);
  // Precondition: the MST of cycle 0 begins at the receiver before the cycle-1 start and
  // ends after it.
  const Time mst_out = on_bit_grid(cycle_time(first, 97, t), t);
  const std::array<std::uint8_t, 1> phase{4};
  const Time mst_in = mst_out + kFibre;
  ASSERT_LT(mst_in + 23 * t.bit + 4 * t.mclk(), first + cycle(1));
  ASSERT_GT(mst_in + static_cast<Time>(line_bits(0xFF, phase)) * t.bit, first + cycle(1));
  run_cycles(4);
  const auto s = sent();
  ASSERT_EQ(s.size(), 4u);  // the transmit telegram of every cycle
  for (int n = 0; n < 4; ++n) EXPECT_EQ(s[static_cast<std::size_t>(n)].start, tx_start(n)) << n;
  // Cycles 0, 1 and 2 missed (cycle 3's header still waits): RERR, NERR 3, VAL kept 0.
  EXPECT_EQ(chip().ram_read(kRx), 0x08FF | 0x2000);
  EXPECT_EQ(chip().ram_read(kRx + 4), 3);
  EXPECT_FALSE(chip().reg_read(kIntStat) & kIntRend);
}

// A TCHK header armed late: the window's opening is not forgotten.
//
// docs/telegram-processing.md §5: a TCHK = 1 header takes a telegram when "its opening flag
// began while the counter was between the step out of TRT − 2 and the step out of TRT + 2".
// A header read after the step out of TRT − 2 (here: behind an idle transmit header due later)
// must still refuse a telegram whose opening flag began before that step.
//
// A master alone on a 0.3 µs loop at 2 Mbit/s: its own telegram to address 5 leaves at TRT
// 100 and begins at its receiver at about 100.8 on its counter; the 2 Mbit/s receiver reports
// the address 11.25 µs later. An idle header due at 103 comes in between; then a receive
// header (ACHK, TCHK, address 5) with TRT 104 (window 102..106: the telegram began 1.2 µs
// before it) or TRT 102 (window 100..104: the control, it began inside).
class LateArmedWindow : public ::testing::Test {
 protected:
  static constexpr Time kShortFibre = 300'000;
  static constexpr std::uint16_t kLateTscyc = 1000;
  static constexpr std::uint16_t kLateRx = 0x04C;
  static constexpr std::uint16_t kLateRxData = 0x053;

  LateArmedWindow() : ring(1, kShortFibre) {}

  void start(std::uint16_t rx_time) {
    t = timing_2mbit();
    Chip& m = ring.chip(0);
    program_master(m, t, kLateTscyc, 4);
    words(m, 0x000, {0x060, 0x040});
    transmit_header(m, 0x040, 0x5005, 100, 2, 0x047);  // every cycle, to address 5
    words(m, 0x044, {0x8002, 0x1111, 0x2222});
    transmit_header(m, 0x047, 0x4000, 103, 0, 0x04C);  // idle: read, never sent
    words(m, 0x04B, {0x8000});
    receive_header(m, kLateRx, 0x1805, rx_time, 2, 0x060);
    words(m, 0x051, {0x8002, 0, 0, 0});
    end_marker(m, 0x060, 500);
    enable_transmission(m);
    ring.run_for(555'555);
    first = ceil_to(ring.scheduler.now(), t.mclk());
    start_master(m);
  }

  Ring ring;
  Timing t;
  Time first = 0;
};

TEST_F(LateArmedWindow, TelegramThatBeganBeforeTheWindowOpenedIsNotTaken) {
  start(104);
  // Precondition: the telegram began at the receiver before the step out of 102 and was
  // reported after the step out of 103 (when the idle header armed the receive header).
  const Time begins = on_bit_grid(cycle_time(first, 100, t), t) + kShortFibre;
  ASSERT_LT(begins, cycle_time(first, 102, t));
  ASSERT_GT(begins + (225 * t.bit) / 10, cycle_time(first, 103, t));
  ring.run_for(static_cast<Time>(kLateTscyc) * sim::kMicrosecond - sim::kMicrosecond);
  Chip& m = ring.chip(0);
  // Missed (doc §5 "Missed header: RERR = 1, NERR + 1 ... the data stay as they are").
  EXPECT_EQ(m.ram_read(kLateRx) & 0x2000, 0x2000) << "RERR";
  EXPECT_EQ(m.ram_read(kLateRx + 4), 1) << "NERR";
  EXPECT_EQ(m.ram_read(kLateRxData), 0) << "data of a telegram outside the window was stored";
}

TEST_F(LateArmedWindow, ControlTelegramThatBeganInsideTheWindowIsTaken) {
  start(102);
  ring.run_for(static_cast<Time>(kLateTscyc) * sim::kMicrosecond - sim::kMicrosecond);
  Chip& m = ring.chip(0);
  EXPECT_EQ(m.ram_read(kLateRx), 0x1805 | 0x0400);
  EXPECT_EQ(m.ram_read(kLateRx + 4), 0);
  EXPECT_EQ(m.ram_read(kLateRxData), 0x1111);
  EXPECT_EQ(m.ram_read(kLateRxData + 1), 0x2222);
}

}  // namespace
}  // namespace sercon::chip

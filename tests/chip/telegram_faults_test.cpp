// Bad DPRAM contents (docs/telegram-processing.md, "Bad lists"): a pointer loop, a pointer
// or container beyond the RAM, a list without end marker, containers without LASTDC. Each
// stops that list for the rest of the cycle and counts a list fault; nothing hangs, the
// next cycle starts afresh, and the MSTs go on.
#include <gtest/gtest.h>

#include "sercon/chip/telegram_processor.hpp"
#include "telegram_bench.hpp"

namespace sercon::chip {
namespace {

using namespace telegram_testing;

constexpr std::uint16_t kTscyc = 100;

class BadList : public ::testing::Test {
 protected:
  explicit BadList(ChipConfig config = {}) : ring(1, 1'000'000, config) {}

  void start() {
    ring.run_for(555'555);
    t = timing_16mbit();
    program_master(chip(), t, kTscyc, 4);
    enable_transmission(chip());
    start_master(chip());
  }
  Chip& chip() { return ring.chip(0); }
  TelegramProcessor& tp() { return *ring.stations[0].tp; }
  void run_cycles(int n) { ring.run_for(n * kTscyc * sim::kMicrosecond); }
  std::size_t list_telegrams() const {
    std::size_t n = 0;
    for (const Seen& s : ring.fibres[0]->seen)
      if (s.data.size() != 1) ++n;
    return n;
  }
  std::size_t msts() const {
    std::size_t n = 0;
    for (const Seen& s : ring.fibres[0]->seen)
      if (s.data.size() == 1) ++n;
    return n;
  }

  Ring ring;
  Timing t;
};

TEST_F(BadList, PointerLoopStopsTheListOncePerCycle) {
  words(chip(), 0, {0x040, 0x040});
  transmit_header(chip(), 0x040, 0x5005, 20, 1, 0x040);  // PT points at itself
  words(chip(), 0x044, {0x8001, 0x1234});
  start();
  run_cycles(3);
  EXPECT_EQ(list_telegrams(), 3u);  // sent once per cycle, then the loop is found
  EXPECT_EQ(tp().list_faults(), 3u);
  EXPECT_EQ(msts(), 3u);
  EXPECT_FALSE(chip().reg_read(kIntStat) & kIntEndmk);
}

TEST_F(BadList, PointerBeyondTheRamStopsTheList) {
  words(chip(), 0, {0x7FE, 0x7FE});  // a header whose TLEN / PT words lie beyond 0x7FF
  chip().ram_write(0x7FE, 0x5005);
  chip().ram_write(0x7FF, 20);
  start();
  run_cycles(2);
  EXPECT_EQ(list_telegrams(), 0u);
  EXPECT_EQ(tp().list_faults(), 2u);
  EXPECT_EQ(msts(), 2u);
}

TEST_F(BadList, ContainerBeyondTheRamSendsNothing) {
  words(chip(), 0, {0x7F0, 0x7F0});
  transmit_header(chip(), 0x7F0, 0x5005, 20, 100, 0x7F0);
  chip().ram_write(0x7F4, 0x8000 | 100);  // 100 data words from 0x7F5: beyond the RAM
  start();
  run_cycles(2);
  EXPECT_EQ(list_telegrams(), 0u);
  EXPECT_EQ(tp().list_faults(), 2u);
}

// "For a receive, its header not updated" (docs/telegram-processing.md, "Bad lists"): the
// receive buffer's second word lies beyond the RAM. The word inside the RAM is stored
// before the fault is found (TelegramRam: a run is done word by word up to the RAM's end).
TEST_F(BadList, ReceiveBufferBeyondTheRamLeavesTheHeaderAlone) {
  words(chip(), 0, {0x040, 0x040});
  transmit_header(chip(), 0x040, 0x5005, 20, 2, 0x7F8);  // to itself, 1 µs later
  words(chip(), 0x044, {0x8002, 0x1111, 0x2222});
  receive_header(chip(), 0x7F8, 0x0805, 0, 2, 0x060);  // ACHK, address 5
  words(chip(), 0x7FD, {0x8002, 0});                   // data at 0x7FF and 0x800
  end_marker(chip(), 0x060, 90);
  start();
  run_cycles(2);
  EXPECT_EQ(list_telegrams(), 2u);
  EXPECT_EQ(tp().list_faults(), 2u);
  EXPECT_EQ(chip().ram_read(0x7F8), 0x0805);  // neither VAL nor RERR
  EXPECT_EQ(chip().ram_read(0x7FC), 0);       // NERR
  EXPECT_EQ(chip().ram_read(0x7FF), 0x1111);
}

TEST_F(BadList, KindTenIsNoEndMarker) {
  words(chip(), 0, {0x040, 0x040});
  transmit_header(chip(), 0x040, 0x5005, 20, 1, 0x050);
  words(chip(), 0x044, {0x8001, 0x1234});
  chip().ram_write(0x050, 0x8000);  // bits 15..14 = 10: neither header nor end marker
  start();
  run_cycles(2);
  EXPECT_EQ(list_telegrams(), 2u);
  EXPECT_EQ(tp().list_faults(), 2u);
  EXPECT_FALSE(chip().reg_read(kIntStat) & kIntEndmk);
}

TEST_F(BadList, TransmitContainersWithoutLastdcRunIntoTheRamEnd) {
  words(chip(), 0, {0x040, 0x040});
  transmit_header(chip(), 0x040, 0x5005, 20, 1, 0x050);
  // Containers of LEN 0 without LASTDC: one control word each, up to the end of the RAM.
  start();
  run_cycles(1);
  EXPECT_EQ(list_telegrams(), 0u);
  EXPECT_EQ(tp().list_faults(), 1u);
}

TEST_F(BadList, UnprogrammedListWaitsHarmlessly) {
  // All-zero RAM: COMPT1 = 0 names word 0, a receive header (kind 00) with TCHK = 0 that
  // waits for a telegram all cycle. Only MSTs come back, and they are no list telegrams.
  start();
  run_cycles(3);
  EXPECT_EQ(list_telegrams(), 0u);
  EXPECT_EQ(tp().list_faults(), 0u);
  EXPECT_EQ(msts(), 3u);
}

class BadList410B : public BadList {
 protected:
  BadList410B() : BadList(config()) {}
  static ChipConfig config() {
    ChipConfig c;
    c.variant = Variant::Sercon410B;
    c.sbaud16 = true;
    return c;
  }
};

TEST_F(BadList410B, PointerIntoTheMissingUpperKilowordStopsTheList) {
  // Delta spec 2.5: the 410B has 1024 words; PT has 11 bits (datasheet 4.2.1), so 0x400
  // and above point beyond its RAM.
  words(chip(), 0, {0x040, 0x040});
  transmit_header(chip(), 0x040, 0x5005, 100, 1, 0x400);  // after the 24 µs MST
  words(chip(), 0x044, {0x8001, 0x1234});
  ring.run_for(555'555);
  t = timing_2mbit();
  program_master(chip(), t, kTscyc * 10, 4);
  enable_transmission(chip());
  start_master(chip());
  ring.run_for(2 * kTscyc * 10 * sim::kMicrosecond);
  EXPECT_EQ(list_telegrams(), 2u);
  EXPECT_EQ(tp().list_faults(), 2u);
}

// A fault found in a receive telegram's containers at its detection, after the walk moved on.
//
// docs/telegram-processing.md §2 "Bad lists": "Any of these stops the list for the rest of
// the cycle and counts a list fault: ... a pointer, header word, container or buffer beyond
// the RAM ... The telegram being assembled is not sent (or, for a receive, its header not
// updated)." A master alone on a 1 µs loop at 16 Mbit/s: it sends to itself (address 5) at
// 20, a receive header takes the telegram, then a transmit header (address 6, 60) and an end
// marker (90). The receive container's buffer runs beyond the RAM (found at the detection,
// after the walk moved on to the transmit header): the address-6 telegram and INT_ENDMK must
// not come in that cycle. Control: the same list with the buffer inside the RAM.
class ReceiveFault : public ::testing::Test {
 protected:
  ReceiveFault() : ring(1, 1'000'000) {}

  void start(std::uint16_t rx) {
    Chip& m = ring.chip(0);
    words(m, 0, {0x040, 0x040});
    transmit_header(m, 0x040, 0x5005, 20, 2, rx);
    words(m, 0x044, {0x8002, 0x1111, 0x2222});
    receive_header(m, rx, 0x0805, 0, 2, 0x060);  // ACHK, address 5, TCHK = 0
    words(m, rx + 5, {0x8002, 0});               // buffer at rx + 7, rx + 8
    transmit_header(m, 0x060, 0x5006, 60, 1, 0x066);
    words(m, 0x064, {0x8001, 0x6666});
    end_marker(m, 0x066, 90);
    ring.run_for(555'555);
    t = timing_16mbit();
    program_master(m, t, kTscyc, 4);
    enable_transmission(m);
    m.reg_write(kIntStat, 0xFFFF);
    start_master(m);
    ring.run_for(kTscyc * sim::kMicrosecond - sim::kMicrosecond);  // one cycle
  }
  std::size_t sent_to(std::uint8_t address) const {
    std::size_t n = 0;
    for (const Seen& s : ring.fibres[0]->seen)
      if (s.address == address) ++n;
    return n;
  }

  Ring ring;
  Timing t;
};

TEST_F(ReceiveFault, BufferBeyondTheRamStopsTheRestOfTheList) {
  start(0x7F8);  // buffer at 0x7FF and 0x800: beyond the RAM
  ASSERT_EQ(ring.stations[0].tp->list_faults(), 1u);
  EXPECT_EQ(sent_to(6), 0u) << "the list went on after the fault";
  EXPECT_EQ(ring.chip(0).reg_read(kIntStat) & kIntEndmk, 0) << "INT_ENDMK";
}

TEST_F(ReceiveFault, ControlBufferInsideTheRamListGoesOn) {
  start(0x050);
  ASSERT_EQ(ring.stations[0].tp->list_faults(), 0u);
  EXPECT_EQ(sent_to(6), 1u);
  EXPECT_EQ(ring.chip(0).reg_read(kIntStat) & kIntEndmk, kIntEndmk);
}

}  // namespace
}  // namespace sercon::chip

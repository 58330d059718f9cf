// Phases 3 and 4 with the real driver's master DPRAM layout of sercos-facts §5, word for
// word where the facts give the words, on the four-drive 2 Mbit/s ring whose values facts §4
// records (IDN2 = 2000, IDN6 = 92, 336, 580, 824, IDN89 = 1782, IDN9 = 1, 9, 17, 25,
// IDN10 = 32; MDT records of 8 bytes, facts §2). Every telegram's start on every fibre is
// computed from the headers, the fibre delays, the receiver / repeater delays and the
// counter rules (telegram_bench.hpp), and the data each DPRAM holds must arrive where the
// layout says.
//
// What the facts leave open is filled in here, and said where it is:
// - the receive block of 37 words per drive: header (5 words), one data container
//   (control word, POS, buffer); the control word is read like the MDT's (SCMASTER, SVFL,
//   NSV = drive - 1, LEN = 2 + 2 cyclic words) with LASTDC, POS 0;
// - "0x8000 on the last" is read as LASTDC added to the last container's control word;
// - the MDT header's time is IDN89 (T2) on the master's counter (docs/telegram-processing.md
//   §3: a master's header times count from its cycle start); the receive headers' times are
//   where the ATs reach the master (the driver measures them; here they are computed);
// - the drives' own lists (the facts describe the master only): AT at T1 = IDN6, the MDT
//   from its record at IDN9.
// The SVFL containers go through the default service-channel port, which sends and stores
// the DPRAM words as they are (docs/telegram-processing.md §8).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <vector>

#include "telegram_bench.hpp"

namespace sercon::chip {
namespace {

using namespace telegram_testing;

constexpr std::size_t kDrives = 4;
constexpr Time kFibre = 1'000'000;
constexpr std::uint16_t kTscyc = 2000;                                       // IDN2
constexpr std::array<std::uint16_t, kDrives + 1> kT1{0, 92, 336, 580, 824};  // IDN6
constexpr std::uint16_t kT2 = 1782;                                          // IDN89
constexpr std::array<std::uint16_t, kDrives + 1> kIdn9{0, 1, 9, 17, 25};
constexpr std::uint16_t kIdn10 = 32;
constexpr std::uint16_t kAtWords = 4;  // status, service info, 2 cyclic words
// Facts §5 addresses.
constexpr std::uint16_t kCompt0List = 0x00B;
constexpr std::uint16_t kCompt1List = 0x020;
constexpr std::uint16_t kBlockWords = 37;
constexpr std::uint16_t kMdtHeader = 0x160;
constexpr std::uint16_t kMdtContainers = 0x164;
constexpr std::uint16_t kEndMarker = 0x26C;
// The drives' lists.
constexpr std::uint16_t kSlaveAt = 0x100;
constexpr std::uint16_t kSlaveMdt = 0x109;
constexpr std::uint16_t kSlaveMdtData = kSlaveMdt + 7;
constexpr std::uint16_t kSlaveEnd = 0x11B;
constexpr std::uint16_t kSlaveOnlyEnd = 0x120;

std::uint16_t block(std::size_t k) {
  return static_cast<std::uint16_t>(kCompt1List + kBlockWords * (k - 1));
}
std::uint16_t mdt_container(std::size_t k) {
  return static_cast<std::uint16_t>(kMdtContainers + 5 * (k - 1));
}
std::uint16_t nsv(std::size_t k) { return static_cast<std::uint16_t>((k - 1) << 11); }

// The words of cycle n: the MDT record for drive k (facts §4 IDN 134: drive on, enable,
// halt/restart; info 0; two cyclic command words) and drive k's AT (IDN 135 operating).
std::array<std::uint16_t, 4> record(int n, std::size_t k) {
  const auto v = static_cast<std::uint16_t>(static_cast<std::size_t>(n) << 4 | k);
  return {0xE000, 0x0000, static_cast<std::uint16_t>(0x1000 | v), static_cast<std::uint16_t>(~v)};
}
std::array<std::uint16_t, 4> at_words(int n, std::size_t k) {
  const auto v = static_cast<std::uint16_t>(static_cast<std::size_t>(n) << 4 | k);
  return {0xC000, 0x0000, static_cast<std::uint16_t>(0x2000 | v),
          static_cast<std::uint16_t>(v * 3)};
}

// Where cycle 0's telegrams start on each fibre (fibre i leaves chip i), from the rules.
struct Expected {
  std::array<std::vector<Time>, kDrives + 1> starts;
  std::array<Time, kDrives + 1> at_back{};  // AT k at the master's RxD
  std::array<Time, kDrives + 1> mdt_in{};   // MDT at drive k's RxD
  std::array<Time, kDrives + 1> load{};     // drive k's counter load
  Time mdt = 0;
};

Expected expect(Time cycle_start, const Timing& t, std::uint8_t phase) {
  Expected e;
  const std::array<std::uint8_t, 1> phase_byte{phase};
  const Time mst_len = static_cast<Time>(line_bits(0xFF, phase_byte)) * t.bit;
  const Time mst = on_bit_grid(cycle_start, t);
  e.starts[0].push_back(mst);
  Time in = mst + kFibre;
  for (std::size_t k = 1; k <= kDrives; ++k) {
    e.load[k] = detection(in + mst_len, t);
    const Time rep = repeated(in, t);
    e.starts[k].push_back(rep);
    in = rep + kFibre;
  }
  for (std::size_t k = 1; k <= kDrives; ++k) {
    const Time at = on_bit_grid(cycle_time(e.load[k], kT1[k], t), t);
    e.starts[k].push_back(at);
    Time at_in = at + kFibre;
    for (std::size_t j = k + 1; j <= kDrives; ++j) {
      const Time rep = repeated(at_in, t);
      e.starts[j].push_back(rep);
      at_in = rep + kFibre;
    }
    e.at_back[k] = at_in;
  }
  e.mdt = on_bit_grid(cycle_time(cycle_start, kT2, t), t);
  e.starts[0].push_back(e.mdt);
  Time mdt_in = e.mdt + kFibre;
  for (std::size_t k = 1; k <= kDrives; ++k) {
    e.mdt_in[k] = mdt_in;
    const Time rep = repeated(mdt_in, t);
    e.starts[k].push_back(rep);
    mdt_in = rep + kFibre;
  }
  for (auto& s : e.starts) std::sort(s.begin(), s.end());
  return e;
}

class FactsCp34 : public ::testing::Test {
 protected:
  FactsCp34() : ring(kDrives + 1, kFibre) {}

  void SetUp() override {
    t = timing_2mbit();
    ring.run_for(7'777'777);
    first = ceil_to(ring.scheduler.now(), t.mclk());
    e3 = expect(first, t, 3);
    e4 = expect(first, t, 4);
    for (std::size_t k = 1; k <= kDrives; ++k) program_drive(k);
    program_master_layout();
    start_master(ring.chip(0));
  }

  // The master: the whole facts §5 layout.
  void program_master_layout() {
    Chip& m = ring.chip(0);
    program_master(m, t, kTscyc, 3);
    // Fixed words: COMPT0, COMPT1, SCPT0..7 (every 50 words), NMSTERR.
    words(m, 0x000,
          {kCompt0List, kCompt1List, 0x273, 0x2A5, 0x2D7, 0x309, 0x33B, 0x36D, 0x39F, 0x3D1, 0});
    // The CP1/2 list (unused in CP3/4), as facts §5 gives it, its MDT idle (0x4000).
    words(m, 0x00B, {0x1000, 100, 2, 0x014, 0, 0xC002, 0, 0, 0});
    words(m, 0x014, {0x4000, 600, 2, 0x01B, 0xC002, 0x0001, 0});
    words(m, 0x01B, {0xC000, 950});
    // CP3/4: one 37-word receive block per drive from 0x020, header 0x1800 + address
    // (ACHK + TCHK); the last points to the MDT header at 0x160.
    for (std::size_t k = 1; k <= kDrives; ++k) {
      const std::uint16_t at = block(k);
      const auto time = static_cast<std::uint16_t>(counter_at(e3.at_back[k], first, t) - 1);
      const auto next = k == kDrives ? kMdtHeader : block(k + 1);
      receive_header(m, at, static_cast<std::uint16_t>(0x1800 | k), time, kAtWords, next);
      words(m, at + 5, {static_cast<std::uint16_t>(0xC400 | nsv(k) | kAtWords), 0});
    }
    // The MDT header 0x50FF (send every cycle, address 255) at T2, IDN10 bytes long, its
    // containers from 0x164: 0x4400 | n << 11 | (len + 2), LASTDC on the last.
    transmit_header(m, kMdtHeader, 0x50FF, kT2, kIdn10 / 2, kEndMarker);
    for (std::size_t k = 1; k <= kDrives; ++k) {
      const auto last = static_cast<std::uint16_t>(k == kDrives ? 0x8000 : 0);
      m.ram_write(mdt_container(k), static_cast<std::uint16_t>(last | 0x4400 | nsv(k) | 4));
    }
    write_master_data(0);
    // The end marker at 0x26C, time = MDT end + 10 µs (the MDT's longest line time: every
    // bit stuffed that can be).
    const std::vector<std::uint8_t> ones(kIdn10, 0xFF);
    const Time mdt_end = e3.mdt + static_cast<Time>(line_bits(0xFF, ones)) * t.bit;
    tend = static_cast<std::uint16_t>(counter_at(mdt_end, first, t) + 10);
    end_marker(m, kEndMarker, tend);
    enable_transmission(m);
  }

  // Drive k: COMPT0 names only an end marker; COMPT1 its AT at T1 = IDN6 and the MDT
  // (address 255, in its time), its record at IDN9.
  void program_drive(std::size_t k) {
    Chip& s = ring.chip(k);
    program_slave(s, t, kTscyc);
    const auto adr = static_cast<std::uint16_t>(k);
    words(s, 0x000, {kSlaveOnlyEnd, kSlaveAt});
    transmit_header(s, kSlaveAt, static_cast<std::uint16_t>(0x5000 | adr), kT1[k], kAtWords,
                    kSlaveMdt);
    s.ram_write(kSlaveAt + 4, 0x8000 | kAtWords);
    write_drive_data(k, 0);
    const auto mdt_time = static_cast<std::uint16_t>(counter_at(e3.mdt_in[k], e3.load[k], t) - 1);
    receive_header(s, kSlaveMdt, 0x18FF, mdt_time, kIdn10 / 2, kSlaveEnd);
    // IDN9 counts bytes from the address byte, 1 for the first drive: word (IDN9 - 1) / 2.
    words(s, kSlaveMdt + 5, {0x8004, static_cast<std::uint16_t>((kIdn9[k] - 1) / 2)});
    end_marker(s, kSlaveEnd, 1950);
    end_marker(s, kSlaveOnlyEnd, 1950);
    enable_transmission(s);
  }

  void write_master_data(int n) {
    for (std::size_t k = 1; k <= kDrives; ++k) {
      const auto r = record(n, k);
      words(ring.chip(0), static_cast<std::uint16_t>(mdt_container(k) + 1),
            {r[0], r[1], r[2], r[3]});
    }
  }
  void write_drive_data(std::size_t k, int n) {
    const auto a = at_words(n, k);
    words(ring.chip(k), kSlaveAt + 5, {a[0], a[1], a[2], a[3]});
  }

  Time cycle(int n) const { return static_cast<Time>(n) * kTscyc * sim::kMicrosecond; }

  Ring ring;
  Timing t;
  Time first = 0;
  Expected e3, e4;
  std::uint16_t tend = 0;
};

std::vector<std::uint8_t> line_data(std::initializer_list<std::array<std::uint16_t, 4>> records) {
  std::vector<std::uint8_t> v;
  for (const auto& r : records) {
    for (std::uint16_t w : r) {
      v.push_back(static_cast<std::uint8_t>(w));
      v.push_back(static_cast<std::uint8_t>(w >> 8));
    }
  }
  return v;
}

// Facts §5 CP3/4 layout, run through CP3 and CP4 (PHAS0 = 3, then 4; facts §5 start-up:
// "PHAS0 = 3 ... PHAS0 = 4"), new data written by the hosts in every cycle:
// - every start on every fibre where the rules put it (facts §2 cycle: the MST at the
//   cycle start, each AT at T1 after the MST's end at its drive, the MDT at T2;
//   datasheet 4.2.1 TRT), cycle n being cycle 0 moved by n * IDN2;
// - the MDT to address 255 carries the four records in container order (datasheet 4.2.2,
//   facts §2 "one record per drive at byte offset IDN 9"), each AT its drive's words;
// - every receive header VAL = 1, RERR = 0, NERR = 0, with the cycle's words in its buffer
//   (datasheet 4.2.1), every drive its record (datasheet 4.2.2 POS); no MST error.
TEST_F(FactsCp34, TelegramsGoOutWhenAndWithWhatTheLayoutSays) {
  constexpr int kCycles = 40;  // 20 in CP3, 20 in CP4
  std::array<std::vector<Time>, kDrives + 1> expected;
  for (int n = 0; n < kCycles; ++n) {
    const std::uint8_t phase = n < kCycles / 2 ? 3 : 4;
    const Expected& e = phase == 3 ? e3 : e4;
    for (std::size_t i = 0; i <= kDrives; ++i) {
      for (Time s : e.starts[i]) expected[i].push_back(s + cycle(n));
    }
    // In the cycle's last 5 µs, after the end markers (the master's and the drives'):
    // check the cycle, then write the next one's data and phase.
    ring.scheduler.run_until(first + cycle(n + 1) - 5 * sim::kMicrosecond);
    Chip& m = ring.chip(0);
    for (std::size_t k = 1; k <= kDrives; ++k) {
      const std::uint16_t at = block(k);
      EXPECT_EQ(m.ram_read(at), 0x1800 | 0x0400 | k) << "cycle " << n << " AT " << k;
      EXPECT_EQ(m.ram_read(at + 4), 0) << "cycle " << n << " AT " << k;
      const auto a = at_words(n, k);
      for (std::uint16_t i = 0; i < kAtWords; ++i) {
        EXPECT_EQ(m.ram_read(static_cast<std::uint16_t>(at + 7 + i)), a[i])
            << "cycle " << n << " AT " << k << " word " << i;
      }
      Chip& s = ring.chip(k);
      EXPECT_EQ(s.ram_read(kSlaveMdt), 0x18FF | 0x0400) << "cycle " << n << " drive " << k;
      EXPECT_EQ(s.ram_read(kSlaveMdt + 4), 0) << "cycle " << n << " drive " << k;
      const auto r = record(n, k);
      for (std::uint16_t i = 0; i < 4; ++i) {
        EXPECT_EQ(s.ram_read(static_cast<std::uint16_t>(kSlaveMdtData + i)), r[i])
            << "cycle " << n << " drive " << k << " word " << i;
      }
      EXPECT_EQ(s.reg_read(kPhase) >> 8, phase) << "cycle " << n << " drive " << k;  // PHASR
      write_drive_data(k, n + 1);
    }
    write_master_data(n + 1);
    if (n + 1 == kCycles / 2) m.reg_write(kPhase, 4);
  }
  for (std::size_t i = 0; i <= kDrives; ++i) {
    std::vector<Time> starts;
    for (const Seen& s : ring.fibre_from(i).seen) starts.push_back(s.start);
    EXPECT_EQ(starts, expected[i]) << "fibre " << i;
  }
  // What left the master in the last cycle: the MST with phase 4, then the MDT.
  const auto& out = ring.fibre_from(0).seen;
  ASSERT_EQ(out.size(), 2u * kCycles);
  EXPECT_EQ(out[2 * kCycles - 2].data, std::vector<std::uint8_t>{4});
  const Seen& mdt = out.back();
  const int n = kCycles - 1;
  EXPECT_EQ(mdt.address, 0xFF);
  EXPECT_EQ(mdt.data, line_data({record(n, 1), record(n, 2), record(n, 3), record(n, 4)}));
  // Drive 4's AT, as it left drive 4 in the last cycle (facts §2: address + status + info +
  // cyclic data).
  const auto& last = ring.fibre_from(kDrives).seen;
  const Seen& at4 = last[last.size() - 2];
  EXPECT_EQ(at4.address, kDrives);
  EXPECT_EQ(at4.data, line_data({at_words(n, kDrives)}));
  for (std::size_t i = 0; i <= kDrives; ++i) {
    EXPECT_EQ(ring.chip(i).ram_read(10), 0) << "NMSTERR " << i;  // datasheet 4.2 word 10
  }
}

// Facts §5: the end marker at 0x26C, "time = MDT end + 10 µs": INT_ENDMK at the step out
// of TEND on the master's counter (datasheet 4.2.3), after the MDT's INT_TEND.
TEST_F(FactsCp34, EndMarkerComesTenMicrosecondsAfterTheMdt) {
  Chip& m = ring.chip(0);
  const Time endmk = cycle_time(first, tend, t);
  ring.scheduler.run_until(e3.mdt);
  m.reg_write(kIntStat, 0xFFFF);
  ring.scheduler.run_until(endmk - 1);
  EXPECT_TRUE(m.reg_read(kIntStat) & kIntTend);
  EXPECT_FALSE(m.reg_read(kIntStat) & kIntEndmk);
  ring.scheduler.run_until(endmk);
  EXPECT_TRUE(m.reg_read(kIntStat) & kIntEndmk);
}

}  // namespace
}  // namespace sercon::chip

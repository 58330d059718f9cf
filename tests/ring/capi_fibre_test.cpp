// The C API's fibres (include/sercon/sercon.h, docs/chip.md "C API"): chips made with
// sercon_chip_new and joined in a loop by sercon_fibre_new are a SERCOS ring (datasheet §1,
// Fig. 3; facts §2 "Ring"), the same ring ring::Ring builds; breaks, restores and bit errors
// act as docs/serial-and-ring.md ("Fibre") says; bad arguments are refused with a status and
// a message, never a crash (sercon.h: "No call throws or aborts on bad input").
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "../chip/register_words.hpp"
#include "ring_bench.hpp"
#include "sercon/ring/ring.hpp"
#include "sercon/sercon.h"
#include "sercon/wire/encoder.hpp"

namespace sercon::ring {
namespace {

using namespace chip::register_words;
using sim::Time;

constexpr Time kBit = 62'500;   // 16 Mbit/s (SBAUD = SBAUD16 = 0, SCLK 64 MHz)
constexpr Time kMclk = 31'250;  // 32 MHz (the default configuration)
constexpr std::array<double, 3> kLengths = {10.0, 20.0, 30.0};
constexpr Time kStart = 1'234'567;  // the master's REGMODE write, off every grid

// What a host writes into a master (phase 0, 100 µs cycles, repeater off) or a slave
// (repeater on, MST window TCNTST -/+ 5 µs); `write(register, value)` is either API's.
template <typename Write>
void program(Write write, bool master) {
  write(kSerMode, master ? std::uint16_t{0} : kRepon);
  write(kSerCtrl, kTxd1Light);
  write(kClockDiv, std::uint16_t{18 << 8 | 31});  // MCLKST 18, MCLKDIV 31: 1 µs at 32 MHz
  write(kTscyc0, 100);
  write(kTscyc1, 100);
  write(kTcntst, 1);
  if (!master) {
    write(kJtscyc1, static_cast<std::uint16_t>(1 - 5));
    write(kJtscyc2, 6);
  }
}

// Pin changes as (time, level), from either API.
using PinLog = std::vector<std::pair<Time, int>>;

void log_change(void* user, sercon_pin, sercon_level level, int64_t t_ps) {
  static_cast<PinLog*>(user)->emplace_back(t_ps, static_cast<int>(level));
}

void expect_ok(int status) { EXPECT_EQ(status, SERCON_OK) << sercon_last_error(); }

// Master + 2 slaves joined by C API fibres of kLengths, programmed and started as a host
// would, logging every node's RECACTN and the master's IDLE.
struct CRing {
  explicit CRing(const std::array<double, 3>& lengths = kLengths) {
    sim = sercon_sim_new();
    sercon_chip_config config;
    sercon_chip_config_default(&config);
    for (auto& c : chips) c = sercon_chip_new(sim, &config);
    for (std::size_t i = 0; i < 3; ++i) {
      fibres[i] = sercon_fibre_new(chips[i], 1, chips[(i + 1) % 3], lengths[i]);
      EXPECT_NE(fibres[i], nullptr) << sercon_last_error();
      expect_ok(sercon_on_pin_change(chips[i], SERCON_PIN_RECACTN, log_change, &recactn[i]));
      program([this, i](std::uint16_t a, std::uint16_t v) { write(i, a, v); }, i == 0);
    }
    expect_ok(sercon_on_pin_change(chips[0], SERCON_PIN_IDLE, log_change, &master_idle));
  }
  ~CRing() { sercon_sim_free(sim); }
  CRing(const CRing&) = delete;
  CRing& operator=(const CRing&) = delete;

  void write(std::size_t chip, std::uint16_t address, std::uint16_t value) {
    expect_ok(sercon_reg_write(chips[chip], address, value));
  }
  std::uint16_t read(std::size_t chip, std::uint16_t address) {
    const std::int32_t v = sercon_reg_read(chips[chip], address);
    EXPECT_GE(v, 0) << sercon_last_error();
    return static_cast<std::uint16_t>(v);
  }
  void start() {
    run_to(kStart);
    write(0, kSerMode, static_cast<std::uint16_t>(read(0, kSerMode) | kRegmode));
  }
  void run_to(Time t) { expect_ok(sercon_sim_run_until(sim, t)); }

  sercon_sim* sim = nullptr;
  std::array<sercon_chip*, 3> chips{};
  std::array<sercon_fibre*, 3> fibres{};
  std::array<PinLog, 3> recactn;
  PinLog master_idle;
};

Time ceil_to(Time t, Time grid) { return (t + grid - 1) / grid * grid; }

// Where the master's MST, sent at `sent`, comes back to its RxD: each fibre's delay (5 ns
// per metre) and each slave's repeater (2 bit times, rounded up to the SCLK grid;
// docs/serial-and-ring.md "Repeater").
Time mst_back(Time sent) {
  Time t = sent + 50'000;          // 10 m to slave 1
  t = testing::repeated(t, kBit);  // slave 1's repeater
  t += 100'000;                    // 20 m to slave 2
  t = testing::repeated(t, kBit);  // slave 2's repeater
  return t + 150'000;              // 30 m back to the master
}

TEST(CapiFibre, ALoopOfFibresIsTheRingRingBuilds) {
  CRing c;
  c.start();
  c.run_to(sim::kMillisecond);

  sim::Scheduler scheduler;
  RingOptions options;
  options.fibre_lengths_m.assign(kLengths.begin(), kLengths.end());
  Ring ring(scheduler, chip::ChipConfig{}, chip::ChipConfig{}, 2, options);
  std::array<PinLog, 3> recactn;
  for (std::size_t i = 0; i < 3; ++i) {
    ring.node(i).pin(chip::Pin::RECACTN).watch([&scheduler, &log = recactn[i]](sim::Level l) {
      log.emplace_back(scheduler.now(), static_cast<int>(l));
    });
    program([&ring, i](std::uint16_t a, std::uint16_t v) { ring.node(i).reg_write(a, v); }, i == 0);
  }
  scheduler.run_until(kStart);
  ring.master().reg_write(kSerMode,
                          static_cast<std::uint16_t>(ring.master().reg_read(kSerMode) | kRegmode));
  scheduler.run_until(sim::kMillisecond);

  for (std::size_t i = 0; i < 3; ++i) {
    // Phase 0, 100 µs cycles from 1.25 µs: by 1 ms ten MSTs, nothing else (no lists), each
    // passing every RxD: RECACTN low, then high (Table 1).
    EXPECT_EQ(c.recactn[i].size(), 20u) << "node " << i;
    EXPECT_EQ(c.recactn[i], recactn[i]) << "node " << i;
    for (std::uint16_t a = 0; a <= 0x2A; ++a) {
      EXPECT_EQ(c.read(i, a), ring.node(i).reg_read(a)) << "node " << i << " register " << a;
    }
    for (std::uint16_t w = 0; w < 2048; ++w) {
      ASSERT_EQ(sercon_ram_read(c.chips[i], w), ring.node(i).ram_read(w)) << "node " << i;
    }
  }
  // The master's own MST goes out at its first cycle start: the MCLK edge after the REGMODE
  // write (docs/timing.md §3, "Master with the internal timer"), TCYCSTART = 0 µs later
  // (reset value, docs/registers.md), on the bit grid. It comes back after the fibres and
  // repeaters: the master's RECACTN falls there.
  const Time cycle_start = ceil_to(kStart, kMclk);
  const Time sent = ceil_to(cycle_start, kBit);
  ASSERT_FALSE(c.master_idle.empty());
  ASSERT_FALSE(c.recactn[0].empty());
  EXPECT_EQ(c.master_idle.front(), std::make_pair(sent, int{SERCON_LOW}));  // IDLE low: MST out
  EXPECT_EQ(c.recactn[0].front(), std::make_pair(mst_back(sent), 0));
  // TCYCDEL (docs/telegram-processing.md §3, decision): the master's counter at the
  // detection of its returning MST, end + 5.5 bit + 3 MCLK up to the next MCLK edge (facts
  // §5 t_start). The counter is TCNTST = 1 from the cycle start and steps every µs from
  // MCLKST = 18 MCLK periods after it (docs/timing.md §2).
  wire::LineEncoder encoder(true);
  const wire::EncodedFrame mst = encoder.telegram(0xFF, std::vector<std::uint8_t>{0});  // phase 0
  const Time end = mst_back(sent) + static_cast<Time>(mst.end_bit - mst.start_bit) * kBit;
  const Time detected = testing::detection(end, kBit, kMclk);
  const Time first_step = cycle_start + 18 * kMclk;
  const auto tcycdel =
      static_cast<std::uint16_t>(1 + (detected - first_step) / sim::kMicrosecond + 1);
  EXPECT_EQ(c.read(0, kTcycdel), tcycdel);
  EXPECT_EQ(sercon_fibre_delay_ps(c.fibres[2]), 150'000);
}

// docs/serial-and-ring.md, "Fibre" and "Line monitor": the far end is dark from the break;
// FIBBR rises FIBBRTIM (0xFF after reset) bit times later; restored, the idle fill's edges
// clear it at once.
TEST(CapiFibre, ABreakRaisesFibbrAtTheMasterAndARestoreClearsIt) {
  CRing c;
  c.start();
  c.run_to(500 * sim::kMicrosecond);
  ASSERT_FALSE(c.read(0, kSerCtrl) & kFibbr);
  const Time broken = 510 * sim::kMicrosecond;
  expect_ok(sercon_fibre_break(c.fibres[2], broken));
  EXPECT_EQ(sercon_fibre_broken(c.fibres[2]), 0);  // not yet: at its time
  c.run_to(broken + 255 * kBit - 1);
  EXPECT_EQ(sercon_fibre_broken(c.fibres[2]), 1);
  EXPECT_FALSE(c.read(0, kSerCtrl) & kFibbr);
  c.run_to(broken + 255 * kBit);
  EXPECT_TRUE(c.read(0, kSerCtrl) & kFibbr);
  EXPECT_TRUE(c.read(0, kIntStat) & kIntFibbr);
  EXPECT_FALSE(c.read(1, kSerCtrl) & kFibbr);  // the other fibres still carry light

  expect_ok(sercon_fibre_restore(c.fibres[2], sercon_sim_now_ps(c.sim)));
  EXPECT_EQ(sercon_fibre_broken(c.fibres[2]), 0);
  c.run_to(sercon_sim_now_ps(c.sim) + 1);
  EXPECT_FALSE(c.read(0, kSerCtrl) & kFibbr);
}

// docs/serial-and-ring.md, "Fibre": bit errors are seeded, so the same seed gives the same
// errors and the same chips; p = 0 flips nothing.
TEST(CapiFibre, BitErrorsAreSeeded) {
  std::array<std::int64_t, 2> flipped{};
  std::array<std::vector<std::int32_t>, 2> master_ram;
  for (std::size_t run = 0; run < 2; ++run) {
    CRing c;
    expect_ok(sercon_fibre_set_bit_error_rate(c.fibres[1], 1e-3, 42));
    c.start();
    c.run_to(3 * sim::kMillisecond);
    flipped[run] = sercon_fibre_bit_errors(c.fibres[1]);
    for (std::uint32_t w = 0; w < 2048; ++w)
      master_ram[run].push_back(sercon_ram_read(c.chips[0], w));
    EXPECT_EQ(sercon_fibre_bit_errors(c.fibres[0]), 0);
  }
  EXPECT_GT(flipped[0], 0);
  EXPECT_EQ(flipped[0], flipped[1]);
  EXPECT_EQ(master_ram[0], master_ram[1]);
}

// Freeing a chip frees the fibres to and from it: the next node's RxD goes dark (FIBBR
// after 255 bit times), nothing dangles, and the freed pin and RxD take a new fibre.
TEST(CapiFibre, FreeingAChipFreesItsFibresAndTheRingCanCloseWithout) {
  CRing c;
  c.start();
  c.run_to(300 * sim::kMicrosecond);
  sercon_chip_free(c.chips[1]);
  c.chips[1] = nullptr;
  const Time freed = sercon_sim_now_ps(c.sim);
  c.run_to(freed + 255 * kBit);
  EXPECT_TRUE(c.read(2, kSerCtrl) & kFibbr);  // slave 2 lost its fibre
  c.run_to(sercon_sim_now_ps(c.sim) + 10 * sim::kMicrosecond);
  EXPECT_TRUE(c.read(0, kSerCtrl) & kFibbr);  // its repeater passes the darkness on
  sercon_fibre* shortcut = sercon_fibre_new(c.chips[0], 1, c.chips[2], 5.0);
  ASSERT_NE(shortcut, nullptr) << sercon_last_error();
  c.run_to(sercon_sim_now_ps(c.sim) + 100 * sim::kMicrosecond);
  EXPECT_FALSE(c.read(2, kSerCtrl) & kFibbr);
  EXPECT_FALSE(c.read(0, kSerCtrl) & kFibbr);
  // The ring is closed again: the facts §5 driver's check, INTSTAT cleared and no line
  // fault latched since.
  c.write(0, kIntStat, 0xFFFF);
  c.run_to(sercon_sim_now_ps(c.sim) + 300 * sim::kMicrosecond);
  EXPECT_FALSE(c.read(0, kIntStat) & (kIntFibbr | kIntRdist));
  sercon_fibre_free(shortcut);
  c.run_to(sercon_sim_now_ps(c.sim) + 255 * kBit);
  EXPECT_TRUE(c.read(2, kSerCtrl) & kFibbr);  // freed: its RxD is dark
}

// sercon.h: every error is a status (or NULL) and a message naming what is wrong.
TEST(CapiFibre, BadArgumentsAreRefusedWithAMessage) {
  CRing c;
  sercon_sim* other_sim = sercon_sim_new();
  sercon_chip_config config;
  sercon_chip_config_default(&config);
  sercon_chip* stranger = sercon_chip_new(other_sim, &config);
  sercon_chip* spare = sercon_chip_new(c.sim, &config);
  const auto refused = [](sercon_fibre* f, const std::string& says) {
    EXPECT_EQ(f, nullptr);
    EXPECT_NE(std::string(sercon_last_error()).find(says), std::string::npos)
        << sercon_last_error();
  };
  refused(sercon_fibre_new(nullptr, 1, spare, 1.0), "from is NULL");
  refused(sercon_fibre_new(spare, 1, nullptr, 1.0), "to is NULL");
  refused(sercon_fibre_new(spare, 0, spare, 1.0), "no TxD pin 0");
  refused(sercon_fibre_new(spare, 7, spare, 1.0), "no TxD pin 7");
  refused(sercon_fibre_new(spare, 1, stranger, 1.0), "different sims");
  refused(sercon_fibre_new(c.chips[0], 1, spare, 1.0), "TxD1 of that chip feeds a fibre");
  refused(sercon_fibre_new(spare, 1, c.chips[1], 1.0), "RxD of that chip has a fibre");
  refused(sercon_fibre_new(spare, 1, spare, -1.0), "length");
  refused(sercon_fibre_new(spare, 1, spare, std::nan("")), "length");
  refused(sercon_fibre_new(spare, 1, spare, std::numeric_limits<double>::infinity()), "length");
  // A refused fibre left nothing behind: the spare's TxD1 and RxD take a loopback.
  sercon_fibre* loop = sercon_fibre_new(spare, 1, spare, 0.0);
  ASSERT_NE(loop, nullptr) << sercon_last_error();
  EXPECT_EQ(sercon_fibre_delay_ps(loop), 0);

  EXPECT_EQ(sercon_fibre_set_bit_error_rate(loop, 1.5, 1), SERCON_ERR_ARGUMENT);
  EXPECT_NE(std::string(sercon_last_error()).find("not a probability"), std::string::npos);
  EXPECT_EQ(sercon_fibre_set_bit_error_rate(loop, -0.1, 1), SERCON_ERR_ARGUMENT);
  EXPECT_EQ(sercon_fibre_set_bit_error_rate(loop, std::nan(""), 1), SERCON_ERR_ARGUMENT);
  c.run_to(1000);
  EXPECT_EQ(sercon_fibre_break(loop, 999), SERCON_ERR_RANGE);
  EXPECT_NE(std::string(sercon_last_error()).find("before now"), std::string::npos);
  EXPECT_EQ(sercon_fibre_restore(loop, 0), SERCON_ERR_RANGE);
  EXPECT_EQ(sercon_fibre_break(nullptr, 2000), SERCON_ERR_ARGUMENT);
  EXPECT_EQ(sercon_fibre_restore(nullptr, 2000), SERCON_ERR_ARGUMENT);
  EXPECT_EQ(sercon_fibre_broken(nullptr), SERCON_ERR_ARGUMENT);
  EXPECT_EQ(sercon_fibre_delay_ps(nullptr), SERCON_ERR_ARGUMENT);
  EXPECT_EQ(sercon_fibre_bit_errors(nullptr), SERCON_ERR_ARGUMENT);
  EXPECT_EQ(sercon_fibre_set_bit_error_rate(nullptr, 0.0, 1), SERCON_ERR_ARGUMENT);
  sercon_fibre_free(nullptr);  // ignored
  sercon_sim_free(other_sim);
}

// sercon.h SERCON_ERR_UNSUPPORTED: in a ring where every node repeats (REPON on in the
// master too) an MST shorter than the ring delay (1 km fibres: 15 µs round, the MST 3.7 µs)
// goes round for ever, and each cycle adds one; the model stops with a message saying so
// (docs/serial-and-ring.md, "Ring"), and the C API does not call it a model fault.
TEST(CapiFibre, ARingWhereEveryNodeRepeatsIsUnsupportedNotInternal) {
  CRing c({1000.0, 1000.0, 1000.0});
  c.write(0, kSerMode, kRepon);  // the master repeats as well
  c.start();
  int status = SERCON_OK;
  for (int ms = 1; ms <= 20 && status == SERCON_OK; ++ms) {
    status = sercon_sim_run_until(c.sim, ms * sim::kMillisecond);
  }
  EXPECT_EQ(status, SERCON_ERR_UNSUPPORTED);
  EXPECT_NE(std::string(sercon_last_error()).find("every node repeats"), std::string::npos)
      << sercon_last_error();
}

// sercon.h: inside a pin callback no fibre is made or freed; a break at now waits for the
// end of the event that called it.
struct InCallback {
  sercon_chip* chip = nullptr;
  sercon_fibre* fibre = nullptr;
  sercon_fibre* made = nullptr;
  int break_status = 1;
  int broken_inside = -1;
  bool done = false;
  std::string error;
};

void act_inside(void* user, sercon_pin, sercon_level level, int64_t t_ps) {
  auto* s = static_cast<InCallback*>(user);
  if (s->done || level != SERCON_LOW) return;
  s->done = true;
  s->made = sercon_fibre_new(s->chip, 2, s->chip, 1.0);
  s->error = sercon_last_error();
  sercon_fibre_free(s->fibre);
  s->break_status = sercon_fibre_break(s->fibre, t_ps);
  s->broken_inside = sercon_fibre_broken(s->fibre);
}

TEST(CapiFibre, InsideAPinCallbackNoFibreIsMadeOrFreedAndABreakWaits) {
  CRing c;
  InCallback s;
  s.chip = c.chips[2];
  s.fibre = c.fibres[2];
  expect_ok(sercon_on_pin_change(c.chips[0], SERCON_PIN_IDLE, act_inside, &s));
  c.start();
  c.run_to(200 * sim::kMicrosecond);
  ASSERT_TRUE(s.done);
  EXPECT_EQ(s.made, nullptr);
  EXPECT_NE(s.error.find("not allowed inside a pin callback"), std::string::npos) << s.error;
  EXPECT_EQ(s.break_status, SERCON_OK);
  EXPECT_EQ(s.broken_inside, 0);
  EXPECT_EQ(sercon_fibre_broken(c.fibres[2]), 1);  // still there, and broken since
}

}  // namespace
}  // namespace sercon::ring

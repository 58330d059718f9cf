// Chips wired into a ring for the telegram-processor tests: a master and slaves on one
// scheduler, each TxD1 into the next chip's RxD through a test fibre with a fixed delay
// that logs every telegram leaving a chip. Everything a chip does is programmed as host
// software does it, through reg_write / ram_write. The arithmetic the tests use to compute
// expected line times stands on its own (datasheet, facts §5 formulas, the documented
// decisions), independent of the model's code.
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "register_words.hpp"
#include "sercon/chip/chip.hpp"
#include "sercon/chip/line.hpp"
#include "sercon/chip/line_decode_memo.hpp"
#include "sercon/chip/serial_unit.hpp"
#include "sercon/chip/settled_line.hpp"
#include "sercon/chip/telegram_processor.hpp"
#include "sercon/sim/scheduler.hpp"
#include "sercon/wire/decoder.hpp"
#include "sercon/wire/encoder.hpp"

namespace sercon::chip::telegram_testing {

using sim::Time;

using namespace register_words;

// One telegram seen leaving a chip's TxD1.
struct Seen {
  Time start = 0;
  Time end = 0;
  std::uint8_t address = 0;
  std::vector<std::uint8_t> data;
  bool ok = false;
};

// A fibre from a TxD to an RxD with a fixed delay; optionally flips one line bit of the
// n-th telegram it carries (a bit error on the way). It passes each announcement (line.hpp)
// on at once; `seen` logs the telegrams that really leave the chip, each when it starts
// (through a SettledLine: one taken back before it starts never appears).
class TestFibre final : public LineListener {
 public:
  TestFibre(sim::Scheduler& scheduler, Time delay, LineListener* target)
      : delay_(delay), target_(target), log_(*this), settled_(scheduler, log_) {}
  TestFibre(const TestFibre&) = delete;
  TestFibre& operator=(const TestFibre&) = delete;

  void line_condition(Time at, LineCondition condition, Time bit_period) override {
    settled_.line_condition(at, condition, bit_period);
    if (target_) target_->line_condition(at + delay_, condition, bit_period);
  }
  void line_burst(const LineBurst& burst) override {
    settled_.line_burst(burst);
    const bool corrupt = corrupt_countdown_ > 0 && --corrupt_countdown_ == 0;
    if (!target_) return;
    LineBurst out = burst;
    out.start += delay_;
    if (corrupt) {
      wire::LineBits bits = *burst.bits;
      wire::LineBits flipped;
      for (std::size_t i = 0; i < bits.size(); ++i) {
        flipped.push_back(i == corrupt_bit_ ? !bits[i] : bits[i]);
      }
      out.bits = chip::share_bits(std::move(flipped));
    }
    target_->line_burst(out);
  }
  // A lazy hop through this fibre (line.hpp): taken as line_burst() takes it, handed back
  // for the sender to deliver. So the rings built of these fibres run the chips' lazy hops,
  // as ring::Ring does. A telegram to corrupt takes line_burst().
  bool pass_through(const LineBurst& burst, LineListener*& next, const LineBurst*& out,
                    chip::PassedBursts&) override {
    if (target_ == nullptr || corrupt_countdown_ > 0) return false;
    settled_.line_burst(burst);
    passed_ = LineBurst{burst.start + delay_, burst.bit_period, burst.bits};
    next = target_;
    out = &passed_;
    return true;
  }

  // The `n`-th telegram from now (1 = the next) gets line bit `bit` inverted.
  void corrupt(unsigned n, std::size_t bit) {
    corrupt_countdown_ = n;
    corrupt_bit_ = bit;
  }
  void cut() { target_ = nullptr; }
  // A break as ring::Fibre::break_now has it (docs/serial-and-ring.md, "Fibre"): the far end
  // sees Dark from `at` (>= now), which cuts a telegram crossing it there, and nothing after
  // it until restore_far_end, which gives it the idle fill from `at` on.
  void break_far_end(Time at) {
    if (!target_) return;
    target_->line_condition(at, LineCondition::Dark, 0);
    broken_ = target_;
    target_ = nullptr;
  }
  void restore_far_end(Time at, Time bit_period) {
    if (!broken_) return;
    target_ = broken_;
    broken_ = nullptr;
    target_->line_condition(at, LineCondition::Idle, bit_period);
  }
  Time delay() const { return delay_; }

  std::vector<Seen> seen;

 private:
  // Takes each telegram when it starts.
  class Log final : public LineListener {
   public:
    explicit Log(TestFibre& fibre) : fibre_(fibre) {}
    void line_condition(Time, LineCondition, Time) override {}
    void line_burst(const LineBurst& burst) override {
      Seen s;
      s.start = burst.start;
      s.end = burst.end();
      const BurstDecode& decode = decode_burst(burst.bits);
      if (!decode.frames.empty()) {
        s.address = decode.frames.front().address;
        s.data = decode.frames.front().data;
        s.ok = decode.frames.front().ok();
      }
      fibre_.seen.push_back(std::move(s));
    }

   private:
    TestFibre& fibre_;
  };

  Time delay_;
  LineListener* target_;
  LineListener* broken_ = nullptr;  // the far end while broken
  unsigned corrupt_countdown_ = 0;
  std::size_t corrupt_bit_ = 0;
  LineBurst passed_;  // the last burst handed back by pass_through, as it reaches target_
  Log log_;
  SettledLine settled_;
};

// Timing registers of one rate as a real driver computes them (facts §5): MCLKDIV gives
// the 1 µs tick, TCNTST = floor(t_start + 1), MCLKST = int((TCNTST - t_start) f + 1) with
// t_start = 5.5 t_bit + 3.5 / f_MCLK.
struct Timing {
  std::int64_t mclk_hz = 32'000'000;
  Time bit = 62'500;  // 16 Mbit/s
  std::uint16_t mclkdiv = 31;
  std::uint16_t tcntst = 1;
  std::uint16_t mclkst = 18;

  // The picosecond helpers below work on whole-picosecond grids (ceil_to); an MCLK such as
  // 24 MHz (41 666.67 ps) would need the chip's MclkGrid, so it is refused rather than
  // rounded into expectations that drift from the chip's exact edges.
  Time mclk() const {
    if (mclk_hz <= 0 || sim::kSecond % mclk_hz != 0) {
      throw std::logic_error("telegram_testing::Timing: MCLK " + std::to_string(mclk_hz) +
                             " Hz has no whole-picosecond period");
    }
    return sim::kSecond / mclk_hz;
  }
  std::int64_t tick_edges() const { return mclkdiv + 1; }
};

inline Timing timing_16mbit() { return Timing{}; }
// 2 Mbit/s, 32 MHz: t_start = 2.75 + 0.109375 µs; TCNTST = 3; MCLKST = int(4.5 + 1) = 5.
inline Timing timing_2mbit() { return Timing{32'000'000, 500'000, 31, 3, 5}; }

struct Station {
  std::unique_ptr<Chip> chip;
  TelegramProcessor* tp = nullptr;
  SerialUnit* serial = nullptr;
};

class Ring {
 public:
  // Chip 0 is the master; fibre i runs from chip i to chip i + 1 (the last back to 0).
  Ring(std::size_t chips, Time fibre_delay, ChipConfig config = {}) {
    for (std::size_t i = 0; i < chips; ++i) {
      Station s;
      s.chip = std::make_unique<Chip>(scheduler, config);
      s.tp = s.chip->unit<TelegramProcessor>();
      s.serial = s.chip->unit<SerialUnit>();
      stations.push_back(std::move(s));
    }
    for (std::size_t i = 0; i < chips; ++i) {
      Station& next = stations[(i + 1) % chips];
      fibres.push_back(std::make_unique<TestFibre>(scheduler, fibre_delay, &next.serial->rxd()));
    }
    for (std::size_t i = 0; i < chips; ++i) stations[i].serial->connect_txd(1, *fibres[i]);
  }

  Chip& chip(std::size_t i) { return *stations[i].chip; }
  TestFibre& fibre_from(std::size_t i) { return *fibres[i]; }
  void run_for(Time t) { scheduler.run_until(scheduler.now() + t); }

  sim::Scheduler scheduler;
  std::vector<Station> stations;
  std::vector<std::unique_ptr<TestFibre>> fibres;
};

// --- host software ------------------------------------------------------------------------

inline std::uint16_t rate_bits(const Timing& t) {
  return t.bit == 500'000 ? static_cast<std::uint16_t>(kEntsbaud | kSwbaud16 | kSwbaud) : 0;
}

// Registers every station needs; the list and the mode come after.
inline void program_common(Chip& chip, const Timing& t, std::uint16_t tscyc) {
  chip.reg_write(kSerCtrl, kTxd1Light);
  chip.reg_write(kClockDiv, static_cast<std::uint16_t>(t.mclkst << 8 | t.mclkdiv));
  chip.reg_write(kTscyc0, tscyc);
  chip.reg_write(kTscyc1, tscyc);
  chip.reg_write(kTcntst, t.tcntst);
}

// Slave: repeater on, a generous MST window (TCNTST -/+ 5 µs).
inline void program_slave(Chip& chip, const Timing& t, std::uint16_t tscyc) {
  chip.reg_write(kSerMode, static_cast<std::uint16_t>(kRepon | rate_bits(t)));
  program_common(chip, t, tscyc);
  chip.reg_write(kJtscyc1, static_cast<std::uint16_t>(t.tcntst - 5));
  chip.reg_write(kJtscyc2, static_cast<std::uint16_t>(t.tcntst + 5));
}

// Master without its repeater (its own telegrams must not circle the ring forever).
// Cycles begin when start_master() sets REGMODE.
inline void program_master(Chip& chip, const Timing& t, std::uint16_t tscyc, std::uint8_t phase) {
  chip.reg_write(kSerMode, rate_bits(t));
  program_common(chip, t, tscyc);
  chip.reg_write(kPhase, phase);
}

inline void start_master(Chip& chip) {
  chip.reg_write(kSerMode, static_cast<std::uint16_t>(chip.reg_read(kSerMode) | kRegmode));
}

inline void enable_transmission(Chip& chip) { chip.reg_write(kTpCtrl, kEntmt); }

// DPRAM structures (datasheet 4.2; transmit header: docs/telegram-processing.md).
inline void receive_header(Chip& chip, std::uint16_t at, std::uint16_t word0, std::uint16_t time,
                           std::uint16_t length, std::uint16_t next) {
  chip.ram_write(at, word0);
  chip.ram_write(at + 1, time);
  chip.ram_write(at + 2, length);
  chip.ram_write(at + 3, next);
  chip.ram_write(at + 4, 0);  // NERR
}
inline void transmit_header(Chip& chip, std::uint16_t at, std::uint16_t word0, std::uint16_t time,
                            std::uint16_t length, std::uint16_t next) {
  chip.ram_write(at, word0);
  chip.ram_write(at + 1, time);
  chip.ram_write(at + 2, length);
  chip.ram_write(at + 3, next);
}
inline void end_marker(Chip& chip, std::uint16_t at, std::uint16_t tend) {
  chip.ram_write(at, 0xC000);
  chip.ram_write(at + 1, tend);
}
inline void words(Chip& chip, std::uint16_t at, std::initializer_list<std::uint16_t> values) {
  for (std::uint16_t v : values) chip.ram_write(at++, v);
}

// --- expected times, computed from the documented rules ------------------------------------

// A telegram's line length in bits (flags, stuffing), from the wire encoder.
inline std::size_t line_bits(std::uint8_t address, std::span<const std::uint8_t> data) {
  wire::LineEncoder encoder;
  encoder.telegram(address, data);
  return encoder.size();
}

inline Time ceil_to(Time t, Time grid) { return (t + grid - 1) / grid * grid; }

// Serial unit: the receiver detects a telegram at the first MCLK edge at or after its end +
// 5.5 bit + 3 MCLK (facts §5 t_start); a slave's counter loads at its detection of the MST
// (one synchroniser, docs/timing.md "Deriving the driver formulas"). The repeater passes a
// telegram on 2 bit times later, rounded up to the 64 MHz SCLK grid (docs/serial-and-ring.md).
inline Time detection(Time end, const Timing& t) {
  return ceil_to(end + (11 * t.bit + 1) / 2 + 3 * t.mclk(), t.mclk());
}
inline Time repeated(Time in, const Timing& t) { return ceil_to(in + 2 * t.bit, 15'625); }

// Time base (docs/timing.md): after a counter load the counter steps from c to c + 1
// ("cycle time c") at load + MCLKST + (c - TCNTST) ticks. A telegram whose time is c begins
// on the first bit edge at or after that.
inline Time cycle_time(Time load, std::uint16_t c, const Timing& t) {
  return load + (t.mclkst + static_cast<Time>(c - t.tcntst) * t.tick_edges()) * t.mclk();
}
inline Time on_bit_grid(Time at, const Timing& t) { return ceil_to(at, t.bit); }
// The counter at `at` in a cycle whose counter was loaded at `load` (the inverse of
// cycle_time): TCNTST, plus one per tick; tick k at load + MCLKST + (k - 1) ticks.
inline std::uint16_t counter_at(Time at, Time load, const Timing& t) {
  const Time first_tick = load + t.mclkst * t.mclk();
  if (at < first_tick) return t.tcntst;
  return static_cast<std::uint16_t>(t.tcntst + (at - first_tick) / (t.tick_edges() * t.mclk()) + 1);
}

}  // namespace sercon::chip::telegram_testing

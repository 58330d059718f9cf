// A chip on a bench for the timing tests (docs/timing.md): register access at chosen
// times, pins recorded with the time of every change, and the MCLK arithmetic the tests
// use to compute expected times on their own (from the formulas, not from the model).
#pragma once

#include <cstdint>
#include <ostream>
#include <vector>

#include "chip_fixture.hpp"
#include "register_words.hpp"
#include "sercon/chip/cycle_control.hpp"
#include "sercon/chip/interrupts.hpp"
#include "sercon/chip/time_base.hpp"
#include "sercon/chip/watchdog.hpp"
#include "sercon/sim/signal.hpp"

namespace sercon::chip::testing {

using sim::kMicrosecond;
using sim::kMillisecond;
using sim::Level;
using sim::Time;

using namespace register_words;

// A chip reset by the RSTN pin (held low) or by SWRST (register 0x01 bit 1): the tests that
// check a reset leaves an output without a glitch take both ways (docs/chip.md, "Resets").
inline void reset_by(Chip& chip, bool by_pin) {
  if (by_pin) {
    chip.drive(Pin::RSTN, Level::Low);
  } else {
    chip.reg_write(kSerMode, 0x0002);  // SWRST
  }
}

// Every change of a pin, with its time.
class PinLog {
 public:
  struct Change {
    Time at;
    Level level;
    friend bool operator==(const Change&, const Change&) = default;
    friend void PrintTo(const Change& c, std::ostream* os) {
      *os << sim::level_char(c.level) << " at " << c.at << " ps";
    }
  };
  PinLog(const sim::Scheduler& scheduler, sim::Signal& signal) : signal_(signal) {
    handle_ = signal_.watch([this, &scheduler](Level level) {
      changes.push_back({scheduler.now(), level});
    });
  }
  ~PinLog() { signal_.unwatch(handle_); }
  PinLog(const PinLog&) = delete;
  PinLog& operator=(const PinLog&) = delete;

  std::vector<Time> times_of(Level level) const {
    std::vector<Time> out;
    for (const Change& c : changes) {
      if (c.level == level) out.push_back(c.at);
    }
    return out;
  }
  std::vector<Change> changes;

 private:
  sim::Signal& signal_;
  std::size_t handle_;
};

struct TimingBench {
  explicit TimingBench(const ChipConfig& config = {}) : bench(config), chip(*bench.chip) {}

  Time now() const { return bench.scheduler.now(); }
  Time mclk() const { return chip.mclk_period(); }
  void run_to(Time t) { bench.scheduler.run_until(t); }
  void write_at(Time t, std::uint16_t reg, std::uint16_t value) {
    run_to(t);
    chip.reg_write(reg, value);
  }
  std::uint16_t read_at(Time t, std::uint16_t reg) {
    run_to(t);
    return chip.reg_read(reg);
  }
  bool flags_at(Time t, std::uint16_t mask) { return (read_at(t, kIntStat) & mask) == mask; }
  void clear_flags() { chip.reg_write(kIntStat, 0xFFFF); }

  TimeBase& time_base() { return *chip.unit<TimeBase>(); }
  CycleControl& cycles() { return *chip.unit<CycleControl>(); }
  Interrupts& interrupts() { return *chip.unit<Interrupts>(); }
  Watchdog& watchdog() { return *chip.unit<Watchdog>(); }
  sim::Signal& pin(Pin p) { return chip.pin(p); }

  // MCLKDIV for a 1 µs tick at this MCLK, as a driver writes it: f_MCLK in MHz - 1.
  std::uint16_t us_divider() const { return static_cast<std::uint16_t>(kMicrosecond / mclk() - 1); }

  ChipOnBench bench;
  Chip& chip;
};

// First MCLK edge at or after t: MCLK edges are at k * period from time 0 (chip.hpp).
inline Time edge_at_or_after(Time t, Time period) { return (t + period - 1) / period * period; }

}  // namespace sercon::chip::testing

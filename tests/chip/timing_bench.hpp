// A chip on a bench for the timing tests (docs/timing.md): register access at chosen
// times, pins recorded with the time of every change, and the MCLK arithmetic the tests
// use to compute expected times on their own (from the formulas, not from the model).
#pragma once

#include <cstdint>
#include <ostream>
#include <vector>

#include "chip_fixture.hpp"
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

// Register word addresses (register table).
inline constexpr std::uint16_t kSerMode = 0x01;
inline constexpr std::uint16_t kTpCtrl = 0x03;
inline constexpr std::uint16_t kIntStat = 0x04;
inline constexpr std::uint16_t kIntSc = 0x05;
inline constexpr std::uint16_t kIen0A = 0x06;
inline constexpr std::uint16_t kIen1A = 0x07;
inline constexpr std::uint16_t kIen0B = 0x08;
inline constexpr std::uint16_t kIen1B = 0x09;
inline constexpr std::uint16_t kPhase = 0x0A;
inline constexpr std::uint16_t kClockDiv = 0x0E;
inline constexpr std::uint16_t kTscyc0 = 0x0F;
inline constexpr std::uint16_t kTscyc1 = 0x10;
inline constexpr std::uint16_t kTcnt = 0x12;
inline constexpr std::uint16_t kTcntst = 0x13;
inline constexpr std::uint16_t kTcycstart = 0x14;
inline constexpr std::uint16_t kJtscyc1 = 0x15;
inline constexpr std::uint16_t kJtscyc2 = 0x16;
inline constexpr std::uint16_t kTconclk = 0x1A;
inline constexpr std::uint16_t kWconclk = 0x1B;
inline constexpr std::uint16_t kConCtrl = 0x1C;
inline constexpr std::uint16_t kTdivclk = 0x1E;
inline constexpr std::uint16_t kDtdivclk = 0x1F;
inline constexpr std::uint16_t kDivCtrl = 0x20;
inline constexpr std::uint16_t kWdCtrl = 0x28;
inline constexpr std::uint16_t kWdTrig = 0x29;
inline constexpr std::uint16_t kTwdog = 0x2A;

// Bits (register table; the tests spell them out rather than derive them).
inline constexpr std::uint16_t kRegmode = 0x0020;   // 0x01 bit 5
inline constexpr std::uint16_t kPresync = 0x0100;   // 0x01 bit 8
inline constexpr std::uint16_t kCycpol = 0x0001;    // 0x03 bit 0
inline constexpr std::uint16_t kInt0pol = 0x0002;   // 0x03 bit 1
inline constexpr std::uint16_t kInt1pol = 0x0004;   // 0x03 bit 2
inline constexpr std::uint16_t kEntmt = 0x0100;     // 0x03 bit 8
inline constexpr std::uint16_t kIntCycst = 0x0004;  // 0x04 bit 2
inline constexpr std::uint16_t kIntMstEarly = 0x0080;
inline constexpr std::uint16_t kIntMstLate = 0x0100;
inline constexpr std::uint16_t kIntMstMiss = 0x0200;
inline constexpr std::uint16_t kIntConclk = 0x0800;
inline constexpr std::uint16_t kIntDivclk = 0x1000;
inline constexpr std::uint16_t kWindowFlags = kIntMstEarly | kIntMstLate | kIntMstMiss;
inline constexpr std::uint16_t kWdogStart = 0x0001;  // 0x28: WDOG_START / WDOG_STAT
inline constexpr std::uint16_t kIntWdog = 0x0002;    // INT_WDOG / CLR_INT_WDOG
inline constexpr std::uint16_t kWdoutSet = 0x0004;   // WDOUT_SET / WDOUT_STAT
inline constexpr std::uint16_t kEn0IntWdog = 0x0008;
inline constexpr std::uint16_t kEn1IntWdog = 0x0010;
inline constexpr std::uint16_t kWdogMsten = 0x0020;
inline constexpr std::uint16_t kIntRscend = 0x0040;  // INT_RSCEND / CLR_RSCEND
inline constexpr std::uint16_t kEn0IntRscend = 0x0080;
inline constexpr std::uint16_t kEn1IntRscend = 0x0100;
inline constexpr std::uint16_t kPoldivclk = 0x0100;   // 0x20 bit 8
inline constexpr std::uint16_t kDivclkmode = 0x0200;  // 0x20 bit 9

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

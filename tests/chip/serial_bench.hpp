// A chip with its serial unit on a bench: a recorder on TxD1 (the fibre's view), a log of
// pin edges, and helpers that build telegram bursts the way a transmitter upstream would.
#pragma once

#include <cstdint>
#include <memory>
#include <utility>
#include <vector>

#include "chip_fixture.hpp"
#include "register_words.hpp"
#include "sercon/chip/line.hpp"
#include "sercon/chip/serial_unit.hpp"
#include "sercon/chip/settled_line.hpp"
#include "sercon/wire/encoder.hpp"

namespace sercon::chip::testing {

// Word addresses: the tests' one table (register_words.hpp).
using register_words::kIntStat;
using register_words::kLineMon;
using register_words::kSerCtrl;
using register_words::kSerMode;
using register_words::kTxPort;

// 0x01
inline constexpr std::uint16_t kRepon = 1u << 3;
inline constexpr std::uint16_t kPoltxd = 1u << 9;
// 0x02
inline constexpr std::uint16_t kTxoe1 = 1u << 0;
inline constexpr std::uint16_t kTxLight = 1u << 6;
inline constexpr std::uint16_t kLedist = 1u << 7;
inline constexpr std::uint16_t kLemiss = 1u << 8;
inline constexpr std::uint16_t kTmode0 = 1u << 9;
inline constexpr std::uint16_t kTmode1 = 1u << 10;
inline constexpr std::uint16_t kTmode2 = 1u << 11;
using register_words::kFibbr;
using register_words::kRdist;
inline constexpr std::uint16_t kRecact = 1u << 14;
// 0x04
using register_words::kIntFibbr;
using register_words::kIntRdist;

// What a line carries, change by change, with the scheduler's time of each change. The
// announcements (line.hpp) go through a SettledLine first, so each change is logged at the
// moment it happens and superseded announcements never appear: the log is the line as it
// really is (docs/serial-and-ring.md, "Per telegram, not per bit").
class LineRecorder : public LineListener {
 public:
  struct Event {
    sim::Time now = 0;  // when the change happened on the line
    bool burst = false;
    LineCondition condition = LineCondition::Dark;
    sim::Time at = 0;  // condition time or burst start
    sim::Time period = 0;
    chip::SharedBits bits;
  };

  explicit LineRecorder(sim::Scheduler& scheduler)
      : scheduler_(scheduler), log_(*this), settled_(scheduler, log_) {}
  LineRecorder(const LineRecorder&) = delete;
  LineRecorder& operator=(const LineRecorder&) = delete;

  void line_condition(sim::Time at, LineCondition condition, sim::Time period) override {
    settled_.line_condition(at, condition, period);
  }
  void line_burst(const LineBurst& b) override { settled_.line_burst(b); }

  std::vector<Event> bursts() const {
    std::vector<Event> out;
    for (const Event& e : events) {
      if (e.burst) out.push_back(e);
    }
    return out;
  }
  std::vector<Event> conditions() const {
    std::vector<Event> out;
    for (const Event& e : events) {
      if (!e.burst) out.push_back(e);
    }
    return out;
  }
  const Event& last() const { return events.back(); }

  std::vector<Event> events;

 private:
  class Log final : public LineListener {
   public:
    explicit Log(LineRecorder& r) : r_(r) {}
    void line_condition(sim::Time at, LineCondition condition, sim::Time period) override {
      r_.events.push_back(Event{r_.scheduler_.now(), false, condition, at, period, nullptr});
    }
    void line_burst(const LineBurst& b) override {
      r_.events.push_back(
          Event{r_.scheduler_.now(), true, LineCondition::Idle, b.start, b.bit_period, b.bits});
    }

   private:
    LineRecorder& r_;
  };

  const sim::Scheduler& scheduler_;
  Log log_;
  SettledLine settled_;
};

// Every level change of one pin, with its time.
struct PinEdges {
  PinEdges(ChipOnBench& bench, Pin p) {
    bench.chip->pin(p).watch(
        [this, &bench](sim::Level l) { edges.emplace_back(bench.scheduler.now(), l); });
  }
  std::vector<std::pair<sim::Time, sim::Level>> edges;
};

// Chip configs for the four bit rates (delta spec 2.3.1 table, SCLK = 64 MHz).
inline ChipConfig config_at_mbit(int mbit, std::int64_t mclk_hz = 32'000'000) {
  ChipConfig c;
  c.mclk_hz = mclk_hz;
  c.sbaud16 = mbit <= 4;             // compatible mode: 2 / 4 Mbit/s
  c.sbaud = mbit == 2 || mbit == 8;  // the slower of each pair
  return c;
}

inline sim::Time bit_period_of(int mbit) { return sim::kSecond / (mbit * 1'000'000LL); }

// The line bits of one telegram as an upstream transmitter would send them.
inline chip::SharedBits telegram_bits(std::uint8_t address, std::vector<std::uint8_t> data,
                                      bool level_before = true) {
  wire::LineEncoder encoder(level_before);
  encoder.telegram(address, data);
  return chip::share_bits(encoder.take());
}

struct SerialBench : ChipOnBench {
  explicit SerialBench(const ChipConfig& config = {})
      : ChipOnBench(config), unit(*chip->unit<SerialUnit>()), txd1(scheduler) {
    set_sermode_bits(kRepon, false);  // a lone chip: own telegrams only (repeater tests
                                      // switch it on)
    unit.connect_txd(1, txd1);
  }
  // TxD1 driven, optical transmitter on (a driver's 0x007F without the other outputs).
  void light_up(std::uint16_t extra = 0) {
    chip->reg_write(kSerCtrl, static_cast<std::uint16_t>(kTxoe1 | kTxLight | extra));
  }
  void set_sermode_bits(std::uint16_t bits, bool on) {
    const std::uint16_t v = chip->reg_read(kSerMode);
    chip->reg_write(kSerMode, static_cast<std::uint16_t>(on ? v | bits : v & ~bits));
  }
  sim::Time period() const { return unit.bit_period(); }
  // First MCLK edge at or after end + 5.5 bit + 3 MCLK (facts §5, t_start).
  sim::Time detection(sim::Time end) const {
    const sim::Time t = end + 11 * period() / 2 + 3 * chip->mclk_period();
    const sim::Time m = chip->mclk_period();
    return (t + m - 1) / m * m;
  }
  void run_to(sim::Time t) { scheduler.run_until(t); }

  SerialUnit& unit;
  LineRecorder txd1;
};

}  // namespace sercon::chip::testing

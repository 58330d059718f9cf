// Helpers for ring-layer tests: what each chip's receiver reports, a line recorder, and
// the exact times a telegram should reach each place (computed here from bit counts,
// periods and delays, independently of the model).
#pragma once

#include <cmath>
#include <cstdint>
#include <memory>
#include <vector>

#include "sercon/chip/chip.hpp"
#include "sercon/chip/line.hpp"
#include "sercon/chip/serial_unit.hpp"
#include "sercon/chip/settled_line.hpp"
#include "sercon/wire/encoder.hpp"

namespace sercon::ring::testing {

inline constexpr sim::Time kSclk = 15'625;  // 64 MHz

// A fibre's documented delay from its length: 5 ns per metre, rounded to the picosecond
// (docs/serial-and-ring.md, "Fibre"), not read back from the model.
inline sim::Time fibre_delay(double metres) {
  return static_cast<sim::Time>(std::llround(metres * 5'000.0));
}

// The repeater's documented delay: 2 bit times, rounded up to the SCLK grid.
inline sim::Time repeated(sim::Time arrival, sim::Time bit) {
  const sim::Time due = arrival + 2 * bit;
  return (due + kSclk - 1) / kSclk * kSclk;
}

// First MCLK edge at or after end + 5.5 bit + 3 MCLK (facts §5).
inline sim::Time detection(sim::Time end, sim::Time bit, sim::Time mclk) {
  const sim::Time t = end + 11 * bit / 2 + 3 * mclk;
  return (t + mclk - 1) / mclk * mclk;
}

struct Heard {
  sim::Time now, start, end, detected;
  wire::DecodedFrame frame;
};

// Everything one chip's receiver reports. The ear takes the telegram processor's place as
// the receiver's client, so it takes back the processor's ReceiveInterest as well: every
// report is made (docs/serial-and-ring.md, "Receiver", "Only wanted reports").
struct Ear {
  explicit Ear(chip::Chip& c) {
    auto* unit = c.unit<chip::SerialUnit>();
    unit->set_interest(nullptr);
    unit->on_telegram([this, &c](const chip::ReceivedTelegram& t) {
      heard.push_back({c.scheduler().now(), t.start, t.end, t.detected, t.frame});
    });
  }
  std::size_t ok_count() const {
    std::size_t n = 0;
    for (const Heard& h : heard) n += h.frame.ok() ? 1u : 0u;
    return n;
  }
  std::vector<Heard> heard;
};

inline chip::ChipConfig config_at_mbit(int mbit) {
  chip::ChipConfig c;
  c.sbaud16 = mbit <= 4;
  c.sbaud = mbit == 2 || mbit == 8;
  return c;
}
inline sim::Time bit_period_of(int mbit) { return sim::kSecond / (mbit * 1'000'000LL); }

inline chip::SharedBits telegram_bits(std::uint8_t address, std::vector<std::uint8_t> data) {
  wire::LineEncoder encoder(true);
  encoder.telegram(address, data);
  return chip::share_bits(encoder.take());
}

// Records what a line carries, change by change: the announcements (line.hpp) go through
// a SettledLine, so each change is logged at the moment it happens (`now`) and superseded
// announcements never appear (docs/serial-and-ring.md, "Per telegram, not per bit").
class Recorder : public chip::LineListener {
 public:
  struct Event {
    sim::Time now = 0;
    bool burst = false;
    chip::LineCondition condition = chip::LineCondition::Dark;
    sim::Time at = 0;
    sim::Time period = 0;
    chip::SharedBits bits;
  };
  explicit Recorder(sim::Scheduler& s) : scheduler_(s), log_(*this), settled_(s, log_) {}
  Recorder(const Recorder&) = delete;
  Recorder& operator=(const Recorder&) = delete;
  void line_condition(sim::Time at, chip::LineCondition c, sim::Time period) override {
    settled_.line_condition(at, c, period);
  }
  void line_burst(const chip::LineBurst& b) override { settled_.line_burst(b); }
  std::vector<Event> events;

 private:
  class Log final : public chip::LineListener {
   public:
    explicit Log(Recorder& r) : r_(r) {}
    void line_condition(sim::Time at, chip::LineCondition c, sim::Time period) override {
      r_.events.push_back({r_.scheduler_.now(), false, c, at, period, nullptr});
    }
    void line_burst(const chip::LineBurst& b) override {
      r_.events.push_back(
          {r_.scheduler_.now(), true, chip::LineCondition::Idle, b.start, b.bit_period, b.bits});
    }

   private:
    Recorder& r_;
  };

  const sim::Scheduler& scheduler_;
  Log log_;
  chip::SettledLine settled_;
};

}  // namespace sercon::ring::testing

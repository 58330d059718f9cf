#include "sercon/chip/serial_unit_transmitter.hpp"

#include <memory>
#include <stdexcept>
#include <string>

#include "sercon/chip/chip.hpp"
#include "sercon/chip/line_decode_seed.hpp"
#include "sercon/chip/serial_unit.hpp"
#include "sercon/chip/serial_unit_pass_through.hpp"
#include "sercon/chip/serial_unit_repeater.hpp"
#include "sercon/wire/encoder.hpp"

namespace sercon::chip {

SerialTransmitter::SerialTransmitter(SerialUnit& unit)
    : unit_(unit), idle_(unit.chip(), Pin::IDLE, *this) {}

void SerialTransmitter::reset() {
  sent_since_reset_ = false;
  unit_.chip().set_output(Pin::IDLE, true);
  idle_.replan();
}

// The fill starts at release on the TxC grid, line high (a project choice: any level would
// do, NRZI data does not depend on it).
void SerialTransmitter::release() {
  free_at_ = unit_.next_bit_edge(unit_.chip().scheduler().now());
  level_ = true;
}

sim::Time SerialTransmitter::send(sim::Time start, std::uint8_t address,
                                  std::span<const std::uint8_t> data) {
  Chip& chip = unit_.chip();
  const sim::Time now = chip.scheduler().now();
  if (start < now) {
    throw std::invalid_argument("SerialUnit::send: start " + std::to_string(start) +
                                " ps is before now (" + std::to_string(now) + " ps)");
  }
  if (!unit_.running()) throw std::logic_error("SerialUnit::send: the chip is in reset");
  const sim::Time period = unit_.bit_period();
  if (period == 0) throw std::logic_error("SerialUnit::send: the serial clocks are off (OUTZ)");
  const sim::Time begin_at = unit_.next_bit_edge(start);
  if (begin_at < free_at_) {
    throw std::logic_error("SerialUnit::send: a telegram at " + std::to_string(begin_at) +
                           " ps overlaps the own telegram that ends at " +
                           std::to_string(free_at_) + " ps");
  }
  // Idle fill between: `0 1111111` repeated, one level change at fill bits 0, 8, 16, ...
  // Counted unsigned (begin_at >= free_at_, period > 0): no sign corrections.
  const std::uint64_t fill_bits =
      static_cast<std::uint64_t>(begin_at - free_at_) / static_cast<std::uint64_t>(period);
  if (((fill_bits + 7) / 8) % 2 != 0) level_ = !level_;
  // With the receivers' decode, known from what was encoded (docs/serial-and-ring.md,
  // "Receiver").
  LineBurst burst{begin_at, period, encode_seeded(level_, address, data)};
  free_at_ = begin_at + static_cast<sim::Time>(burst.bits->size()) * period;  // burst.end()
  sent_since_reset_ = true;
  unit_.repeater().own(std::move(burst), free_at_, now);  // last use
  idle_.replan();
  return free_at_;
}

bool SerialTransmitter::level_at(sim::Time t) const {
  if (!sent_since_reset_) return true;
  const auto& sent = unit_.repeater().own_telegrams();
  for (std::size_t i = 0; i < sent.size(); ++i) {
    if (sent[i].start <= t && t < sent[i].end()) return false;
  }
  return true;
}

// Back to back telegrams keep IDLE low across the seam.
sim::Time SerialTransmitter::next_change_after(sim::Time t) const {
  if (!sent_since_reset_) return LazyPin::kNever;
  const auto& sent = unit_.repeater().own_telegrams();
  const bool level = level_at(t);
  for (std::size_t i = 0; i < sent.size(); ++i) {
    for (const sim::Time c : {sent[i].start, sent[i].end()}) {
      if (c > t && level_at(c) != level) return c;
    }
  }
  return LazyPin::kNever;
}

}  // namespace sercon::chip

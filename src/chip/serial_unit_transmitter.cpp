#include "sercon/chip/serial_unit_transmitter.hpp"

#include <memory>
#include <stdexcept>
#include <string>

#include "sercon/chip/chip.hpp"
#include "sercon/chip/serial_unit.hpp"
#include "sercon/chip/serial_unit_repeater.hpp"
#include "sercon/wire/encoder.hpp"

namespace sercon::chip {

void SerialTransmitter::cancel() {
  for (const Scheduled& s : queue_) {
    unit_.chip().scheduler().cancel(s.begin);
    unit_.chip().scheduler().cancel(s.end);
  }
  queue_.clear();
}

void SerialTransmitter::reset() {
  cancel();
  unit_.chip().set_output(Pin::IDLE, true);
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
  const sim::Time fill_bits = (begin_at - free_at_) / period;
  if (((fill_bits + 7) / 8) % 2 != 0) level_ = !level_;
  wire::LineEncoder encoder(level_);
  encoder.telegram(address, data);
  level_ = encoder.level();
  auto bits = std::make_shared<const wire::LineBits>(encoder.take());
  Scheduled s;
  s.burst = LineBurst{begin_at, period, std::move(bits)};
  free_at_ = s.burst.end();
  s.begin = chip.scheduler().at(begin_at, [this] { begin(); });
  s.end = chip.scheduler().at(free_at_, [this] { finish(); });
  queue_.push_back(std::move(s));
  return free_at_;
}

void SerialTransmitter::begin() {
  unit_.chip().set_output(Pin::IDLE, false);
  unit_.repeater().own_begin(queue_.front().burst);
}

void SerialTransmitter::finish() {
  queue_.pop_front();
  // Back to back: the next telegram begins in this instant; IDLE stays low, no gap.
  const sim::Time now = unit_.chip().scheduler().now();
  if (!queue_.empty() && queue_.front().burst.start == now) return;
  unit_.chip().set_output(Pin::IDLE, true);
  unit_.repeater().own_end();
}

}  // namespace sercon::chip

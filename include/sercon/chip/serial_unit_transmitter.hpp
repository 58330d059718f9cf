// The transmitter: the telegram processor's telegrams as bursts of exact line bits on the
// TxC grid, the idle fill's level carried on between them, IDLE low while own data goes out
// (datasheet Table 1). A telegram is announced to the repeater, which puts it on the line,
// the moment it is sent (line.hpp): it costs no event. IDLE is computed when read, and
// switched by events only while watched (LazyPin).
#pragma once

#include <cstdint>
#include <span>

#include "sercon/chip/lazy_pin.hpp"
#include "sercon/chip/line.hpp"

namespace sercon::chip {

class SerialUnit;

class SerialTransmitter final : private LazyPin::Source {
 public:
  explicit SerialTransmitter(SerialUnit& unit);
  SerialTransmitter(const SerialTransmitter&) = delete;
  SerialTransmitter& operator=(const SerialTransmitter&) = delete;

  void reset();
  void release();
  // Flattened (every call in it inlined, the coder's too: line_decode_seed.hpp): an own
  // telegram, its coding and its way out through the repeater and TxD, is one function,
  // without the calls' register saves and the bits handle through memory.
  [[gnu::flatten]] sim::Time send(sim::Time start, std::uint8_t address,
                                  std::span<const std::uint8_t> data);
  sim::Time free_at() const { return free_at_; }
  // An own telegram is on the line at `t` (IDLE low; the RS-485 driver is enabled).
  bool sending_at(sim::Time t) const { return !level_at(t); }

 private:
  // LazyPin::Source: IDLE is high unless an own telegram is on the line.
  bool level_at(sim::Time t) const override;
  sim::Time next_change_after(sim::Time t) const override;

  SerialUnit& unit_;
  // The own telegrams are the repeater's (SerialRepeater::own_telegrams: one queue, kept
  // there). False from a reset to the next telegram: SerialUnit::reset resets the repeater
  // after this, so its queue still holds them while this reset replans IDLE.
  bool sent_since_reset_ = false;
  sim::Time free_at_ = 0;  // end of the last telegram (or release)
  bool level_ = true;      // line level at free_at_ (light = true)
  LazyPin idle_;
};

}  // namespace sercon::chip

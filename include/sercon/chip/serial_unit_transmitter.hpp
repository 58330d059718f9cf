// The transmitter: the telegram processor's telegrams as bursts of exact line bits on the
// TxC grid, the idle fill's level carried on between them, IDLE low while own data goes out
// (datasheet Table 1). The bursts go to the repeater, which puts them on the line.
#pragma once

#include <cstdint>
#include <deque>
#include <span>

#include "sercon/chip/line.hpp"
#include "sercon/sim/scheduler.hpp"

namespace sercon::chip {

class SerialUnit;

class SerialTransmitter {
 public:
  explicit SerialTransmitter(SerialUnit& unit) : unit_(unit) {}
  ~SerialTransmitter() { cancel(); }
  SerialTransmitter(const SerialTransmitter&) = delete;
  SerialTransmitter& operator=(const SerialTransmitter&) = delete;

  void reset();
  void release();
  sim::Time send(sim::Time start, std::uint8_t address, std::span<const std::uint8_t> data);
  sim::Time free_at() const { return free_at_; }

 private:
  struct Scheduled {
    LineBurst burst;
    sim::Scheduler::EventId begin, end;
  };
  void begin();
  void finish();
  void cancel();

  SerialUnit& unit_;
  std::deque<Scheduled> queue_;  // own telegrams not yet finished, in time order
  sim::Time free_at_ = 0;        // end of the last telegram (or release)
  bool level_ = true;            // line level at free_at_ (light = true)
};

}  // namespace sercon::chip

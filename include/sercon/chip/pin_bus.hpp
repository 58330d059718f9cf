// The µP bus interface driven through the pins (datasheet Table 1, 3.5.3-3.5.7): strobes
// RDN/WRN in Intel or Motorola mode (BUSMODE1-0), address from A15-0 or from the address
// latch (ADMUX, ALEL, ALEH), chip selects, BHEN and D15-0. Each strobe becomes one
// Chip::bus() cycle: reads at the start of the strobe (the chip then drives its data
// lanes until the strobe ends), writes at its end with D15-0 as they are then; a write's
// start asks for BUSYN (Chip::write_strobe_starts).
#pragma once

#include <cstdint>

#include "sercon/chip/bus.hpp"
#include "sercon/chip/chip_unit.hpp"

namespace sercon::chip {

class Chip;

class PinBus : public ChipUnit {
 public:
  explicit PinBus(Chip& chip);

  void reset(ResetCause cause) override;

  std::uint16_t latched_address() const { return latch_; }
  // Strobes that selected RAM and registers at once (a board fault): no access was made.
  std::uint64_t refused_cycles() const { return refused_; }
  // The result of the last cycle the pins made.
  const BusResult& last_result() const { return last_; }

 private:
  BusStrobes strobes() const;
  void on_strobe_pin();
  void on_latch_pin();
  void drive_address_lines();
  BusCycle sample(bool write) const;
  void run(const BusCycle& cycle);
  void write_starts();
  void release_data_lines();

  Chip& chip_;
  BusStrobes active_;
  std::uint16_t latch_ = 0;
  std::uint16_t driven_ = 0;  // data lines this unit drives for a read in progress
  std::uint64_t refused_ = 0;
  bool write_busy_ = false;  // the write in progress collided at its start
  bool write_cut_ = false;   // the write strobe now held began before a reset: writes nothing
  BusResult last_;
};

}  // namespace sercon::chip

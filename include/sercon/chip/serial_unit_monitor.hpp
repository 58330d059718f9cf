// The line monitor (datasheet Table 1 L_ERRN; register 0x02 RDIST / FIBBR, LEDIST / LEMISS;
// 0x0D RDISTLIM / FIBBRTIM; INTSTAT INT_RDIST / INT_FIBBR):
// - FIBBR: no edge on RxD for max(FIBBRTIM, 8) bit times (the line is Dark or Light). It
//   clears with the next edge.
// - RDIST: max(RDISTLIM, 1) distorted edges in a row. An edge is distorted when it comes
//   from a signal at a bit period other than the receiver's (a telegram, idle fill or zero
//   bits sent at another rate); an edge at the receiver's own rate clears the count and RDIST.
// - INT_RDIST / INT_FIBBR latch when the status bit rises, and a write of 1 does not clear
//   them while it is 1 (Interrupts::set_level); L_ERRN is low while
//   (RDIST & LEDIST) | (FIBBR & LEMISS).
// docs/serial-and-ring.md, "Line monitor".
#pragma once

#include <cstdint>

#include "sercon/chip/serial_unit_input.hpp"
#include "sercon/sim/scheduler.hpp"

namespace sercon::chip {

class SerialUnit;

class LineMonitor {
 public:
  // A healthy line changes level at least every 8 bit times (idle fill), so a shorter
  // FIBBRTIM would flag every idle line: it counts as 8.
  static constexpr std::uint16_t kMinFibbrBits = 8;

  explicit LineMonitor(SerialUnit& unit) : unit_(unit) {}
  ~LineMonitor() { cancel(); }
  LineMonitor(const LineMonitor&) = delete;
  LineMonitor& operator=(const LineMonitor&) = delete;

  void reset();
  void release();
  // RxD went from `before` to `after` now.
  void input_changed(const RxdSegment& before, const RxdSegment& after);
  // RDISTLIM / FIBBRTIM or the bit rate changed.
  void refresh_limits();
  // LEDIST / LEMISS changed.
  void refresh_line_error();

 private:
  void evaluate();  // status and timers for segment_ as it is now
  void set_rdist(bool on);
  void set_fibbr(bool on);
  void cancel();

  SerialUnit& unit_;
  RxdSegment segment_;
  sim::Time period_ = 0;         // the receiver's bit period segment_ is judged by
  std::uint64_t distorted_ = 0;  // distorted edges in a row before segment_
  // Edges of segment_ not judged: before the rate it is judged by took effect, or before
  // release (the count starts there).
  std::uint64_t skipped_ = 0;
  bool rdist_ = false, fibbr_ = false;
  sim::Scheduler::EventId rdist_event_{}, fibbr_event_{};
};

}  // namespace sercon::chip

// The repeater (delta spec 2.3.3, REPON) and the line it feeds: what RxD receives goes on
// to TxD a fixed delay later (kRepeaterDelayBits bit times, rounded up to the SCLK grid),
// the same bits object, unchanged. Own telegrams are inserted: while one is sent nothing
// received is passed on, and a repeated telegram in the way is cut where the own one
// begins (own telegram wins). REPON = 0: only own telegrams and their idle fill leave.
// docs/serial-and-ring.md, "Repeater".
#pragma once

#include <deque>

#include "sercon/chip/line.hpp"
#include "sercon/chip/serial_unit_input.hpp"
#include "sercon/sim/scheduler.hpp"

namespace sercon::chip {

class SerialUnit;

class SerialRepeater {
 public:
  explicit SerialRepeater(SerialUnit& unit) : unit_(unit) {}
  ~SerialRepeater() { cancel(); }
  SerialRepeater(const SerialRepeater&) = delete;
  SerialRepeater& operator=(const SerialRepeater&) = delete;

  void reset();
  void release();
  // RxD changed now (segment.since == now).
  void input(const RxdSegment& segment);
  // The transmitter's own telegram begins / ends now.
  void own_begin(const LineBurst& burst);
  void own_end();
  // REPON or the bit rate changed.
  void refresh();

  // When something that reaches RxD at `t` leaves on TxD.
  sim::Time forward_time(sim::Time t) const;
  bool on() const { return repon_; }

 private:
  struct Pending {
    RxdSegment segment;  // as it leaves TxD
    sim::Scheduler::EventId event;
  };
  void forward();    // the front of pending_ is due
  void show_line();  // the line's condition when no own telegram is in the way
  void cancel();

  SerialUnit& unit_;
  bool repon_ = false;
  bool own_active_ = false;
  RxdSegment forwarded_;         // the received signal as it reaches TxD
  std::deque<Pending> pending_;  // forwards in time order
  sim::Time last_forward_ = 0;
};

}  // namespace sercon::chip

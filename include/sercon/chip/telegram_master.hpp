// The master's MST (docs/telegram-processing.md §3, "Master — counter reference"): sent at every
// internal MST start (CycleControl::on_send_mst) with PHAS0 as its data byte, whatever ENTMT says
// (delta spec 2.6.2); its return around the ring is measured and judged:
//  - TCYCDEL (0x11) = the cycle counter at the returned MST's detection;
//  - outside JTRDEL1..JTRDEL2, or not back (by the step out of JTRDEL2, at the latest by
//    the next MST): INT_RETMST and NMSTERR (RAM word 10) + 1. JTRDEL2 = 0 (reset value,
//    not programmed) switches the window check off; a missing MST still counts.
#pragma once

#include <cstdint>

#include "sercon/chip/field_ref.hpp"
#include "sercon/chip/interrupts.hpp"
#include "sercon/chip/serial_unit.hpp"
#include "sercon/chip/telegram_ram.hpp"
#include "sercon/chip/time_base.hpp"

namespace sercon::chip {

class MasterMst {
 public:
  MasterMst(TimeBase& time_base, Interrupts& interrupts, SerialUnit& serial, TelegramRam& ram);
  MasterMst(const MasterMst&) = delete;
  MasterMst& operator=(const MasterMst&) = delete;

  // Sends the MST now. Returns false when the transmitter is busy or its clocks are off:
  // then no MST goes out in this cycle (an MST error).
  bool send();
  // An error-free MST has been detected at the receiver.
  void returned();
  // Reset: nothing awaited. Does not touch the time base (it may be gone).
  void stop() { out_ = false; }

 private:
  void error();
  void window_ends();

  TimeBase& time_base_;
  RegisterFile& regs_;
  Interrupts& interrupts_;
  SerialUnit& serial_;
  TelegramRam& ram_;
  FieldRef phas0_, tcycdel_, jtrdel1_, jtrdel2_;
  // An MST of this cycle went out and has not come back; judged: its error (missing, or
  // outside the window) is counted, so a late return only measures TCYCDEL.
  bool out_ = false;
  bool judged_ = false;
  TimeBase::CycleEvent window_end_{};
};

}  // namespace sercon::chip

// The SERCON816 watchdog (delta spec 2.6, 2.11.2; docs/timing.md, "Watchdog").
//
// Off after every reset. WDOG_START switches it on; only a reset switches it off again
// (or its own expiry). Switched on, and at every trigger, a down counter is preset with
// TWDOG and counts on its own MCLKDIV divider, restarted at the preset, so it expires
// exactly T_WDOG = (MCLKDIV + 1) * TWDOG / f_MCLK after the trigger. Triggers: 0x42
// written to WDOG_TRIG (0x29, bits 7-0), and in master mode with WDOG_MSTEN the internal
// MST start signal. On expiry: INT_WDOG set, watchdog off, ENTMT and PHAS0 cleared and
// write-protected until INT_WDOG is cleared, and with WDOUT enabled WDOGN low until the
// third tick of the free-running µs divider after expiry (2 to 3 periods).
// The 410B has no watchdog: there this unit does nothing.
#pragma once

#include <functional>

#include "sercon/chip/chip_unit.hpp"
#include "sercon/chip/field_ref.hpp"
#include "sercon/chip/interrupts.hpp"
#include "sercon/chip/tick_alarm.hpp"
#include "sercon/chip/time_base.hpp"

namespace sercon::chip {

class Chip;

class Watchdog : public ChipUnit {
 public:
  using Output = std::function<void(bool high)>;

  // Also listens to CycleControl's MST start (built before it).
  explicit Watchdog(Chip& chip);
  Watchdog(TimeBase& time_base, Interrupts& interrupts, Output wdogn);

  void reset(ResetCause cause) override;

  // The internal MST start signal (CycleControl::on_send_mst): a trigger when the chip is
  // master and WDOG_MSTEN is set (delta spec 2.6.5).
  void mst_started();

  bool running() const { return running_; }
  bool output_active() const { return output_low_; }
  // Expiry time while running.
  sim::Time expires_at() const { return expiry_.pending() ? expiry_.when() : expires_.when(); }

 private:
  void on_control_write(std::uint16_t written);
  void on_trigger_write(std::uint16_t written);
  void load();
  void counted_out();
  void expire();
  void drive_output(bool low);

  TimeBase& time_base_;
  RegisterFile& regs_;
  Interrupts& interrupts_;
  Output wdogn_;
  bool present_;
  FieldRef start_, int_wdog_, wdout_, mst_en_, regmode_, entmt_, phas0_;
  bool running_ = false;
  bool protecting_ = false;  // ENTMT and PHAS0 locked until INT_WDOG is cleared
  bool output_low_ = false;
  DividerTicks ticks_;
  TickAlarm expiry_;   // the count reaches 0000H
  TickAlarm expires_;  // then, after the other events of that edge: unless one triggered
  TickAlarm output_end_;
};

}  // namespace sercon::chip

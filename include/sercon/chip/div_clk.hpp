// The DIV_CLK output (delta spec 2.7, 2.11.1.3; datasheet Table 1; docs/timing.md,
// "DIV_CLK"). Pulses are 1 µs wide (one µs tick: MCLKDIV + 1 MCLK periods) and start at
// cycle times of the cycle counter, planned at each cycle start from the registers then:
//   mode 0 (DIVCLKMODE = 0, the 410B's only mode): NDIVCLK pulses in each cycle, the
//     first at TDIVCLK, then every DTDIVCLK µs; pulses that would start at or after the
//     cycle time TSCYC are dropped;
//   mode 1 (816): one pulse at TDIVCLK every NDIVCLK cycles, the first in the first
//     cycle that starts with NDIVCLK != 0 after NDIVCLK was 0 or mode 0 was chosen (at a
//     cycle start or by any write, also within a cycle).
// NDIVCLK = 0: never. POLDIVCLK: 0 active high, 1 active low. INT_DIVCLK at each start.
#pragma once

#include <functional>
#include <vector>

#include "sercon/chip/chip_unit.hpp"
#include "sercon/chip/field_ref.hpp"
#include "sercon/chip/interrupts.hpp"
#include "sercon/chip/tick_alarm.hpp"
#include "sercon/chip/time_base.hpp"

namespace sercon::chip {

class Chip;

class DivClk : public ChipUnit {
 public:
  using Output = std::function<void(bool high)>;

  explicit DivClk(Chip& chip);
  DivClk(TimeBase& time_base, Interrupts& interrupts, Output pin);

  void reset(ResetCause cause) override;

  bool active() const { return active_; }

 private:
  void plan(const CycleStart& start);
  void plan_pulses(const CycleStart& start, std::int64_t n);  // NDIVCLK = n != 0
  void plan_pulse_at(std::int64_t cycle_time);
  void pulse_starts();
  void pulse_ends();
  void drive();
  // The cycle start's plan changes nothing while NDIVCLK = 0, nothing is planned and mode 1
  // is re-armed.
  void refresh_idle();

  TimeBase& time_base_;
  RegisterFile& regs_;
  Interrupts& interrupts_;
  Output pin_;
  FieldRef ndivclk_, poldivclk_, divclkmode_;
  bool active_ = false;
  bool first_due_ = true;  // mode 1: the next cycle with NDIVCLK != 0 pulses (re-armed)
  std::int64_t cycles_since_pulse_ = 0;
  std::vector<TimeBase::CycleEvent> planned_;
  TickAlarm end_;
  TimeBase::CycleListenerId listener_ = 0;
};

}  // namespace sercon::chip

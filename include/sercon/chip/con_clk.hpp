// The CON_CLK output (datasheet Table 1: "becomes active within a communication cycle.
// Time, polarity and width are programmable"; docs/timing.md, "CON_CLK"). Planned at each
// cycle start from TCONCLK and WCONCLK as they read then (writes act from the next cycle
// start): active from cycle time TCONCLK (0x1A) for WCONCLK (0x1B) µs, i.e.
// WCONCLK * (MCLKDIV + 1) MCLK periods; WCONCLK = 0 never; a start at or after the cycle
// time TSCYC is dropped. POLCONCLK (0x1C bit 0): 0 active high, 1 active low. INT_CONCLK
// when it becomes active. A start while still active restarts the width.
#pragma once

#include <cstdint>
#include <functional>

#include "sercon/chip/chip_unit.hpp"
#include "sercon/chip/field_ref.hpp"
#include "sercon/chip/interrupts.hpp"
#include "sercon/chip/tick_alarm.hpp"
#include "sercon/chip/time_base.hpp"

namespace sercon::chip {

class Chip;

class ConClk : public ChipUnit {
 public:
  using Output = std::function<void(bool high)>;

  explicit ConClk(Chip& chip);
  ConClk(TimeBase& time_base, Interrupts& interrupts, Output pin);

  void reset(ResetCause cause) override;

  bool active() const { return active_; }

 private:
  void plan(const CycleStart& start);
  void starts();
  void ends();
  void drive();
  // The cycle start's plan changes nothing while WCONCLK = 0 and nothing is planned or taken.
  void refresh_idle();

  TimeBase& time_base_;
  RegisterFile& regs_;
  Interrupts& interrupts_;
  Output pin_;
  FieldRef polconclk_;
  bool active_ = false;
  std::int64_t width_ = 0;  // WCONCLK (µs) taken at the cycle start
  TimeBase::CycleEvent planned_{};
  TickAlarm end_;
  TimeBase::CycleListenerId listener_ = 0;
};

}  // namespace sercon::chip

// The JTSCYC1/JTSCYC2 window in which the next MST (slave) or CYC_CLK edge (master with
// PRESYNC = 1) must come, and the INT_MSTEARLY / INT_MSTLATE / INT_MSTMISS verdicts
// (facts §5; delta spec 2.6.5; docs/timing.md, "Windows").
//
// In counter terms an on-time MST is detected when the counter, loaded with TCNTST at the
// previous one, reads TSCYC + TCNTST; the driver programs JTSCYC1/2 = TCNTST -/+ JT. So
// the window is TSCYC + JTSCYC1 .. TSCYC + JTSCYC2 in counter values, with JTSCYC1/2 taken
// as signed 16-bit numbers (a driver's TCNTST - JT is often negative).
#pragma once

#include <algorithm>
#include <cstdint>
#include <functional>

#include "sercon/chip/interrupts.hpp"
#include "sercon/chip/time_base.hpp"

namespace sercon::chip {

class CycleWindow {
 public:
  enum class State : std::uint8_t {
    Unsynced,  // no expectation: after reset, mode changes, TSCYC = 0, a master's miss
    Synced,    // the window of the cycle that began with an MST / CYC_CLK
    Missed,    // the last window closed empty (slave: a substitute cycle runs)
  };

  // `closed_empty` runs after INT_MSTMISS when a window closes without an event.
  CycleWindow(TimeBase& time_base, Interrupts& interrupts, std::function<void()> closed_empty);
  CycleWindow(const CycleWindow&) = delete;
  CycleWindow& operator=(const CycleWindow&) = delete;

  // A cycle began now (`start`, as the time base announced it: its count and TSCYC are
  // the counter and the cycle time now): expect the next event one cycle later. TSCYC = 0
  // means the cycle time is not programmed: nothing is expected, so no window closes empty
  // and nothing free-wheels. Inline: a step of every slave's cycle start.
  void expect_next(const CycleStart& start) {
    // No close is pending: the time base dropped one later than now, judge() decided one due
    // now, and a close that ran started this cycle (shift_cycle).
    state_ = State::Unsynced;
    tscyc_ = start.tscyc;
    if (tscyc_ == 0) return;
    opens_ = tscyc_ + jtscyc1_;
    closes_ = tscyc_ + jtscyc2_;
    state_ = start.kind == CycleKind::Substitute ? State::Missed : State::Synced;
    // A window programmed to close before the counter's start closes at the first step.
    // Deferred: mostly the next MST comes first and drops it. An MST's or a master's start
    // has just restarted the divider, with the counter at start.count: the step is ahead.
    const std::int64_t close_at = std::max(closes_, start.count);
    if (start.kind != CycleKind::Substitute) [[likely]] {
      time_base_.defer_after_restart(close_event_, close_at, &CycleWindow::closes);
    } else {
      time_base_.defer_at_cycle_time(close_event_, close_at, &CycleWindow::closes);
    }
  }
  void forget() {  // back to Unsynced
    close_event_.cancel();
    state_ = State::Unsynced;
  }
  // An MST (slave) or CYC_CLK (master) arrives now: raises the flags it earns. A close
  // due at this very instant is decided first, so the order of equal-time events does
  // not matter. Inline: a step of every slave's cycle start.
  void judge(bool master) { judge_at(master, time_base_.mclk().last_at_or_before(now())); }
  // judge() for `now_edge`, the last MCLK edge at or before now (a slave's MST load edge).
  void judge_at(bool master, Edge now_edge) {
    // Mostly the close is still ahead: its time is looked at before the scheduler is asked.
    if (close_event_.when() <= now() && close_event_.pending()) {
      close_event_.cancel();
      close();
    }
    const std::int64_t position = time_base_.count_at(now_edge);
    switch (state_) {
      case State::Unsynced:
        return;
      case State::Synced:
        if (position < opens_) interrupts_.raise(Irq::MstEarly);
        return;
      case State::Missed:
        missed_judged(master, position);
        return;
    }
  }

  State state() const { return state_; }
  std::int64_t opens() const { return opens_; }    // TSCYC + JTSCYC1, counter value
  std::int64_t closes() const { return closes_; }  // TSCYC + JTSCYC2, counter value
  std::uint16_t tscyc() const { return tscyc_; }

 private:
  static constexpr std::uint8_t kJtscyc1 = 0x15;
  static constexpr std::uint8_t kJtscyc2 = 0x16;

  sim::Time now() const { return time_base_.scheduler().now(); }
  void read_fields();
  static void closes(void* window);  // the close event (function + context)
  void close();
  void missed_judged(bool master, std::int64_t position);  // judge() after an empty window

  TimeBase& time_base_;
  Interrupts& interrupts_;
  std::function<void()> closed_empty_;
  State state_ = State::Unsynced;
  std::uint16_t tscyc_ = 0;
  std::int64_t opens_ = 0;
  std::int64_t closes_ = 0;
  // JTSCYC1 / JTSCYC2 as signed numbers, kept as data: read again at every register value
  // change by a listener that runs before all others (RegisterFile::on_change_first).
  std::int16_t jtscyc1_ = 0;
  std::int16_t jtscyc2_ = 0;
  TimeBase::OwnedEvent close_event_;
};

}  // namespace sercon::chip

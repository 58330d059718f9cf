#include "sercon/chip/watchdog.hpp"

#include <utility>

#include "sercon/chip/cycle_control.hpp"
#include "sercon/chip/required_unit.hpp"

namespace sercon::chip {
namespace {

constexpr std::uint8_t kWdCtrl = 0x28;
constexpr std::uint8_t kWdTrig = 0x29;
constexpr std::uint8_t kTwdog = 0x2A;
constexpr std::uint16_t kTriggerValue = 0x42;  // delta spec 2.6.4
constexpr std::int64_t kOutputTicks = 3;       // delta spec 2.6.1: "minimum 2, maximum 3"

}  // namespace

Watchdog::Watchdog(Chip& chip)
    : Watchdog(required_unit<TimeBase>(chip, "Watchdog"),
               required_unit<Interrupts>(chip, "Watchdog"),
               [&chip](bool high) { chip.set_output(Pin::WDOGN, high); }) {
  required_unit<CycleControl>(chip, "Watchdog").on_send_mst([this] { mst_started(); });
}

Watchdog::Watchdog(TimeBase& time_base, Interrupts& interrupts, Output wdogn)
    : time_base_(time_base),
      regs_(time_base.regs()),
      interrupts_(interrupts),
      wdogn_(std::move(wdogn)),
      present_(regs_.variant() == Variant::Sercon816),
      start_(field_ref("WDOG_START", regs_.variant())),
      int_wdog_(field_ref("INT_WDOG", regs_.variant())),
      wdout_(field_ref("WDOUT_SET", regs_.variant())),
      mst_en_(field_ref("WDOG_MSTEN", regs_.variant())),
      regmode_(field_ref("REGMODE", regs_.variant())),
      entmt_(field_ref("ENTMT", regs_.variant())),
      phas0_(field_ref("PHAS0", regs_.variant())),
      expiry_(time_base.scheduler(), time_base.mclk(), [this] { counted_out(); }),
      expires_(time_base.scheduler(), time_base.mclk(), [this] { expire(); }),
      output_end_(time_base.scheduler(), time_base.mclk(), [this] { drive_output(false); }) {
  if (!present_) return;
  regs_.on_write(kWdCtrl,
                 [this](std::uint16_t written, std::uint16_t) { on_control_write(written); });
  regs_.on_write(kWdTrig,
                 [this](std::uint16_t written, std::uint16_t) { on_trigger_write(written); });
  time_base_.on_divider_change([this](Edge edge, std::int64_t period) {
    ticks_.change_period(edge, period);
    expiry_.retime(ticks_, edge);
  });
}

// Delta spec 2.6: "After chip reset the watchdog is OFF"; 2.6.2: a reset's clearing of
// ENTMT / PHAS0 has priority, so the protection ends with it (the register file's reset
// has already dropped the locks and cleared INT_WDOG).
void Watchdog::reset(ResetCause) {
  running_ = false;
  protecting_ = false;
  expiry_.cancel();
  expires_.cancel();
  output_end_.cancel();
  if (present_) drive_output(false);
}

// WDOG_START (W), CLR_INT_WDOG (W1C, done by the register file), WDOUT_SET (W).
void Watchdog::on_control_write(std::uint16_t written) {
  if ((written & start_.mask) != 0 && !running_) {
    running_ = true;
    start_.set(regs_, true);  // reads back as WDOG_STAT
    load();
  }
  if ((written & wdout_.mask) != 0) wdout_.set(regs_, true);  // WDOUT_STAT, until reset
  if (protecting_ && !int_wdog_.on(regs_)) {
    protecting_ = false;
    regs_.lock(entmt_.address, entmt_.mask, false);
    regs_.lock(phas0_.address, phas0_.mask, false);
  }
}

// Delta spec 2.6.4: only the value 42H in bits 7-0 triggers, at any time.
void Watchdog::on_trigger_write(std::uint16_t written) {
  if ((written & 0x00FF) == kTriggerValue && running_) load();
}

void Watchdog::mst_started() {
  if (present_ && running_ && regmode_.on(regs_) && mst_en_.on(regs_)) load();
}

// Delta spec 2.6.3: the down counter is preset with TWDOG and counts at the MCLKDIV rate
// to 0000H. TWDOG = 0 is 0000H already: the watchdog expires at once.
void Watchdog::load() {
  expires_.cancel();  // a trigger at the edge the count ran out loads it again
  const Edge now = time_base_.mclk().first_at_or_after(time_base_.scheduler().now());
  const std::int64_t period = time_base_.tick_period();
  ticks_ = DividerTicks::started_at(now, period, period);
  const std::uint16_t preset = regs_.value(kTwdog);
  if (preset == 0) {
    expiry_.at_edge(now);
  } else {
    expiry_.at_tick(ticks_, preset);
  }
}

// The count has reached 0000H at this edge. A trigger at the same edge (an MST start, whose
// event may run before or after this one) loads the counter again and wins (docs/timing.md,
// "Watchdog"): the expiry is decided after the events already due at this instant.
void Watchdog::counted_out() {
  const sim::Time now = time_base_.scheduler().now();
  expires_.at_edge(time_base_.mclk().last_at_or_before(now));
}

void Watchdog::expire() {
  running_ = false;
  start_.set(regs_, false);  // WDOG_STAT = 0: "it switches off automatically"
  // Delta spec 2.6.2: ENTMT = 0, PHAS0 = 0, not writable until INT_WDOG is cleared.
  entmt_.set(regs_, false);
  phas0_.put(regs_, 0);
  regs_.lock(entmt_.address, entmt_.mask, true);
  regs_.lock(phas0_.address, phas0_.mask, true);
  protecting_ = true;
  // Raised after the locks: a handler that clears INT_WDOG (from a pin callback, which the
  // chip runs when this event is done, or from an output callback of a unit built without
  // a chip, which runs inside raise()) must find the lock in place to lift it.
  interrupts_.raise(Irq::Wdog);
  if (!wdout_.on(regs_)) return;
  // Delta spec 2.6.1: WDOGN "remains active for the next minimum 2, maximum 3 periods".
  drive_output(true);
  const sim::Time now = time_base_.scheduler().now();
  output_end_.at_edge(time_base_.free_tick_after(now, kOutputTicks));
}

void Watchdog::drive_output(bool low) {
  output_low_ = low;
  wdogn_(!low);
}

}  // namespace sercon::chip

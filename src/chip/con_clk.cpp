#include "sercon/chip/con_clk.hpp"

#include <utility>

#include "sercon/chip/required_unit.hpp"

namespace sercon::chip {
namespace {

constexpr std::uint8_t kTconclk = 0x1A;
constexpr std::uint8_t kWconclk = 0x1B;
constexpr std::int64_t kUnprogrammedCycleEnd = 0x10000;  // TSCYC = 0: the counter's range

}  // namespace

ConClk::ConClk(Chip& chip)
    : ConClk(required_unit<TimeBase>(chip, "ConClk"), required_unit<Interrupts>(chip, "ConClk"),
             [&chip](bool high) { chip.set_output(Pin::CON_CLK, high); }) {}

ConClk::ConClk(TimeBase& time_base, Interrupts& interrupts, Output pin)
    : time_base_(time_base),
      regs_(time_base.regs()),
      interrupts_(interrupts),
      pin_(std::move(pin)),
      polconclk_(field_ref("POLCONCLK", regs_.variant())),
      end_(time_base.scheduler(), time_base.mclk(), [this] { ends(); }) {
  listener_ = time_base_.on_cycle_start(this, [](void* con_clk, const CycleStart& start) {
    static_cast<ConClk*>(con_clk)->plan(start);
  });
  refresh_idle();
  // A reset's polarity is driven by reset(), which ends a pulse in progress first.
  regs_.on_change([this](std::uint8_t address) {
    if (address == polconclk_.address && !regs_.resetting()) drive();
    if (address == kWconclk) refresh_idle();
  });
}

void ConClk::reset(ResetCause) {
  time_base_.cancel(planned_);
  planned_ = {};
  end_.cancel();
  active_ = false;
  drive();
  refresh_idle();
}

void ConClk::refresh_idle() {
  time_base_.set_cycle_listener_idle(
      listener_, width_ == 0 && planned_ == TimeBase::CycleEvent{} && regs_.value(kWconclk) == 0);
}

void ConClk::plan(const CycleStart& start) {
  planned_ = {};  // the time base dropped the previous cycle's event
  const std::int64_t cycle_end = start.tscyc == 0 ? kUnprogrammedCycleEnd : start.tscyc;
  const std::uint16_t at = regs_.value(kTconclk);
  // Taken now, as TCONCLK: a WCONCLK written within the cycle acts from the next cycle start
  // (a 0 written after this plan would otherwise give a zero-width pulse with INT_CONCLK).
  width_ = regs_.value(kWconclk);
  if (width_ == 0 || at >= cycle_end) return refresh_idle();
  planned_ = time_base_.at_cycle_time(at, [this] { starts(); });
}

// INT_CONCLK ("CON_CLK became active") last: the pin callbacks it runs see CON_CLK active.
void ConClk::starts() {
  active_ = true;
  drive();
  const Edge now = time_base_.mclk().first_at_or_after(time_base_.scheduler().now());
  end_.at_edge(now + width_ * time_base_.tick_period());
  interrupts_.raise(Irq::ConClk);
}

// The next cycle's start at this very instant continues the output without a gap.
void ConClk::ends() {
  if (time_base_.when(planned_) == time_base_.scheduler().now()) return;
  active_ = false;
  drive();
}

void ConClk::drive() { pin_(active_ != polconclk_.on(regs_)); }

}  // namespace sercon::chip

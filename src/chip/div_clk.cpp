#include "sercon/chip/div_clk.hpp"

#include <utility>

#include "sercon/chip/required_unit.hpp"

namespace sercon::chip {
namespace {

constexpr std::uint8_t kTdivclk = 0x1E;
constexpr std::uint8_t kDtdivclk = 0x1F;
constexpr std::int64_t kUnprogrammedCycleEnd = 0x10000;  // TSCYC = 0: the counter's range

}  // namespace

DivClk::DivClk(Chip& chip)
    : DivClk(required_unit<TimeBase>(chip, "DivClk"), required_unit<Interrupts>(chip, "DivClk"),
             [&chip](bool high) { chip.set_output(Pin::DIV_CLK, high); }) {}

DivClk::DivClk(TimeBase& time_base, Interrupts& interrupts, Output pin)
    : time_base_(time_base),
      regs_(time_base.regs()),
      interrupts_(interrupts),
      pin_(std::move(pin)),
      ndivclk_(field_ref("NDIVCLK", regs_.variant())),
      poldivclk_(field_ref("POLDIVCLK", regs_.variant())),
      divclkmode_(field_ref("DIVCLKMODE", regs_.variant())),
      end_(time_base.scheduler(), time_base.mclk(), [this] { pulse_ends(); }) {
  listener_ = time_base_.on_cycle_start(this, [](void* div_clk, const CycleStart& start) {
    static_cast<DivClk*>(div_clk)->plan(start);
  });
  refresh_idle();
  // A new polarity shows at once, also on an idle output (a reset's is driven by reset(),
  // which ends a pulse in progress first).
  regs_.on_change([this](std::uint8_t address) {
    if (address == poldivclk_.address && !regs_.resetting()) drive();
    if (address == ndivclk_.address) refresh_idle();
  });
  // Delta spec 2.7: a programming of NDIVCLK != 0 restarts mode 1 "after the first cycle",
  // also when the 0 before it lasted less than a cycle: every moment the register holds
  // NDIVCLK = 0 (or mode 0) re-arms, not only a cycle start that sees it.
  regs_.on_write(ndivclk_.address, [this](std::uint16_t, std::uint16_t) {
    if (ndivclk_.get(regs_) == 0 || !divclkmode_.on(regs_)) first_due_ = true;
    refresh_idle();
  });
}

void DivClk::reset(ResetCause) {
  for (auto id : planned_) time_base_.cancel(id);
  planned_.clear();
  end_.cancel();
  active_ = false;
  first_due_ = true;
  cycles_since_pulse_ = 0;
  drive();
  refresh_idle();
}

void DivClk::refresh_idle() {
  time_base_.set_cycle_listener_idle(listener_,
                                     planned_.empty() && first_due_ && ndivclk_.get(regs_) == 0);
}

void DivClk::plan(const CycleStart& start) {
  planned_.clear();  // the time base dropped the previous cycle's events
  const std::int64_t n = ndivclk_.get(regs_);
  if (n == 0) {  // delta spec 2.7: "0 Never becomes active"
    first_due_ = true;
    return refresh_idle();
  }
  plan_pulses(start, n);
}

// Out of line: plan() returns at once with NDIVCLK = 0 (DIV_CLK unused, the usual case)
// without the set-up this needs.
[[gnu::noinline]] void DivClk::plan_pulses(const CycleStart& start, std::int64_t n) {
  const std::int64_t cycle_end = start.tscyc == 0 ? kUnprogrammedCycleEnd : start.tscyc;
  const std::int64_t first = regs_.value(kTdivclk);
  if (!divclkmode_.on(regs_)) {
    first_due_ = true;  // mode 1, if chosen later, starts with a pulse
    const std::int64_t distance = regs_.value(kDtdivclk);
    for (std::int64_t k = 0; k < n; ++k) {
      const std::int64_t at = first + k * distance;
      if (at >= cycle_end || (k > 0 && distance == 0)) break;
      plan_pulse_at(at);
    }
    return;
  }
  // Delta spec 2.7: "goes active the first time in the first SERCOS cycle ... or after the
  // first cycle when NDIVCLK is being programmed to a value not equal zero".
  if (first_due_) {
    first_due_ = false;
    cycles_since_pulse_ = 0;
  } else if (++cycles_since_pulse_ < n) {
    return;
  } else {
    cycles_since_pulse_ = 0;
  }
  if (first < cycle_end) plan_pulse_at(first);
}

void DivClk::plan_pulse_at(std::int64_t cycle_time) {
  const auto id = time_base_.at_cycle_time(cycle_time, [this] { pulse_starts(); });
  if (id != TimeBase::CycleEvent{}) planned_.push_back(id);
}

// INT_DIVCLK ("A DIV_CLK pulse began") last: the pin callbacks it runs see the pulse.
void DivClk::pulse_starts() {
  active_ = true;
  drive();
  const Edge now = time_base_.mclk().first_at_or_after(time_base_.scheduler().now());
  end_.at_edge(now + time_base_.tick_period());
  interrupts_.raise(Irq::DivClk);
}

// A pulse starting at this very instant (DTDIVCLK = 1, or the next cycle's first pulse)
// continues the output instead of a zero-width gap.
void DivClk::pulse_ends() {
  const sim::Time now = time_base_.scheduler().now();
  for (auto id : planned_) {
    if (time_base_.when(id) == now) return;
  }
  active_ = false;
  drive();
}

void DivClk::drive() { pin_(active_ != poldivclk_.on(regs_)); }

}  // namespace sercon::chip

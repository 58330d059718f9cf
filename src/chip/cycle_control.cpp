#include "sercon/chip/cycle_control.hpp"

#include <stdexcept>
#include <string>
#include <utility>

#include "sercon/chip/required_unit.hpp"
#include "sercon/chip/serial_unit.hpp"

namespace sercon::chip {
namespace {

constexpr std::uint8_t kSerMode = 0x01;
constexpr std::uint8_t kPhase = 0x0A;
constexpr std::uint8_t kTscyc0 = 0x0F;
constexpr std::uint8_t kTscyc1 = 0x10;
constexpr std::uint8_t kTcycstart = 0x14;

// Synchroniser depths (docs/timing.md): an MST recognised at t loads the counter at the
// 3rd MCLK edge after the first edge at or after t, 3..4 periods later, the 3.5 / f_MCLK
// of the driver's t_start: the edge the receiver reports it at (kDetectionEdges, the same
// synchroniser); an asynchronous CYC_CLK edge passes two flip-flops.
constexpr Edge kMstSyncEdges = kDetectionEdges;
constexpr Edge kCycClkSyncEdges = 2;
constexpr std::size_t kKeptRecognitions = 8;

}  // namespace

CycleControl::CycleControl(Chip& chip)
    : CycleControl(required_unit<TimeBase>(chip, "CycleControl"),
                   required_unit<Interrupts>(chip, "CycleControl"), chip.pin(Pin::CYC_CLK)) {}

CycleControl::CycleControl(TimeBase& time_base, Interrupts& interrupts, sim::Signal& cyc_clk)
    : time_base_(time_base),
      regs_(time_base.regs()),
      scheduler_(time_base.scheduler()),
      interrupts_(interrupts),
      cyc_clk_(cyc_clk),
      regmode_(field_ref("REGMODE", regs_.variant())),
      presync_(field_ref("PRESYNC", regs_.variant())),
      cycpol_(field_ref("CYCPOL", regs_.variant())),
      window_(time_base, interrupts,
              [this] {
                // Slave: keep the cycle going one TSCYC after the missing MST's slot.
                if (mode_ == Mode::Slave) {
                  time_base_.shift_cycle(
                      window_.tscyc(), [this](const CycleStart& start) { on_cycle_start(start); });
                }
              }),
      next_cycle_(time_base.scheduler(), time_base.mclk(), [this] { master_cycle_start(); }),
      mst_send_(time_base.scheduler(), time_base.mclk(), [this] { mst_due(); }),
      mst_event_(scheduler_.own(&CycleControl::owned_mst_action, this)) {
  cycst_latched_ = interrupts_.latched(Irq::Cycst);
  regs_.on_change_first([this](std::uint8_t) { cycst_latched_ = interrupts_.latched(Irq::Cycst); });
  regs_.on_change([this](std::uint8_t address) { on_register_change(address); });
  cyc_clk_.react([this](sim::Level level) { on_cyc_clk(level); });
  time_base_.on_divider_change(
      [this](Edge edge, std::int64_t period) { on_divider_change(edge, period); });
}

// Only the scheduler is touched here: the time base may be gone already (units are
// destroyed in any order) and cancels the window's event itself.
CycleControl::~CycleControl() {
  cancel_own_events();
  scheduler_.disown(mst_event_);
}

void CycleControl::cancel_own_events() {
  next_cycle_.cancel();
  mst_send_.cancel();
  scheduler_.cancel_owned(mst_event_);
  for (const Recognition& r : recognitions_) scheduler_.cancel(r.event);
  recognitions_.clear();
}

void CycleControl::cancel_all() {
  cancel_own_events();
  window_.forget();
}

void CycleControl::reset(ResetCause) {
  running_ = false;
  cancel_all();
  mode_ = Mode::Slave;
  timer_idle_ = false;
  cyc_clk_high_ = cyc_clk_.level() != sim::Level::Low;
}

void CycleControl::release() {
  running_ = true;
  cyc_clk_high_ = cyc_clk_.level() != sim::Level::Low;
  switch_mode(mode_from_registers());
}

void CycleControl::on_send_mst(std::function<void()> listener) {
  send_mst_listeners_.push_back(std::move(listener));
}

CycleControl::Mode CycleControl::mode_from_registers() const {
  if (!regmode_.on(regs_)) return Mode::Slave;
  return presync_.on(regs_) ? Mode::MasterCycClk : Mode::MasterTimer;
}

// A new mode starts from scratch: no window, no pending master events. The internal
// timer starts a cycle at the next MCLK edge, or idles until TSCYC is programmed.
void CycleControl::switch_mode(Mode mode) {
  cancel_all();
  mode_ = mode;
  timer_idle_ = false;
  if (mode_ == Mode::MasterTimer) start_timer_now();
}

void CycleControl::start_timer_now() {
  if (time_base_.tscyc() == 0) {
    timer_idle_ = true;
    return;
  }
  timer_idle_ = false;
  next_cycle_.at_edge(time_base_.mclk().first_at_or_after(scheduler_.now()));
}

void CycleControl::on_register_change(std::uint8_t address) {
  if (!running_) return;
  if (address == kSerMode) {
    const Mode mode = mode_from_registers();
    if (mode != mode_) switch_mode(mode);
    return;
  }
  const bool cycle_time = address == kTscyc0 || address == kTscyc1 || address == kPhase;
  if (cycle_time && mode_ == Mode::MasterTimer && timer_idle_) start_timer_now();
}

// Inline in the MST and CYC_CLK paths (GCC kept it a call).
[[gnu::always_inline]] inline void CycleControl::recognise_at(sim::Time at,
                                                              sim::Scheduler::Action action,
                                                              bool cyc_clk) {
  // Ids of events that ran stay until a few have gathered (cancelling them is harmless):
  // one MST per cycle need not scan the list each time. The last one has mostly run: its
  // entry is reused.
  const Recognition recognition{scheduler_.at(at, action, this), cyc_clk};
  if (!recognitions_.empty() && !scheduler_.pending(recognitions_.back().event)) {
    recognitions_.back() = recognition;
    return;
  }
  if (recognitions_.size() >= kKeptRecognitions) {
    std::erase_if(recognitions_,
                  [this](const Recognition& r) { return !scheduler_.pending(r.event); });
  }
  recognitions_.push_back(recognition);
}

void CycleControl::cyc_clk_action(void* control) {
  static_cast<CycleControl*>(control)->cyc_clk_recognised();
}

void CycleControl::slave_mst_action(void* control) {
  auto& self = *static_cast<CycleControl*>(control);
  // A recognition runs at its load edge: the first (and last) edge at or after now.
  self.slave_mst(self.time_base_.mclk().first_at_or_after(self.scheduler_.now()));
}

void CycleControl::owned_mst_action(void* control) {
  auto& self = *static_cast<CycleControl*>(control);
  self.slave_mst(self.mst_load_edge_);
}

void CycleControl::mst_detected(sim::Time when) {
  const MclkGrid::EdgeAt load = time_base_.mclk().nth_edge_at(when, kMstSyncEdges);
  if (load.time < scheduler_.now()) refuse_past_load(when, load.time);
  if (!running_) return;
  // Mostly the MST is heard of at its load edge (TelegramProcessor::on_mst): now. The other
  // cases out of line: inline, their queue work made this path save registers.
  if (!scheduler_.owned_pending(mst_event_)) [[likely]] {
    mst_load_edge_ = load.edge;
    if (load.time == scheduler_.now()) [[likely]]
      return scheduler_.arm_owned_now(mst_event_);
  }
  mst_later(load.time);
}

void CycleControl::mst_later(sim::Time load) {
  if (!scheduler_.owned_pending(mst_event_)) return scheduler_.arm_owned(mst_event_, load);
  recognise_at(load, &CycleControl::slave_mst_action, false);
}

void CycleControl::refuse_past_load(sim::Time when, sim::Time load) const {
  throw std::invalid_argument("CycleControl::mst_detected: an MST recognised at " +
                              std::to_string(when) + " ps would load the counter at " +
                              std::to_string(load) + " ps, before now (" +
                              std::to_string(scheduler_.now()) + " ps)");
}

// At `load`, the MST's load edge: now is its time, so it is the last edge at or before now
// (the counter's) and the first at or after (the cycle's start).
void CycleControl::slave_mst(Edge load) {
  if (!running_ || mode_ != Mode::Slave) return;
  window_.judge_at(false, load);
  time_base_.start_cycle_at(load, CycleKind::Mst,
                            [this](const CycleStart& start) { on_cycle_start(start); });
  raise_cycst();
}

// CYC_CLK has a pull-up (datasheet 3.3), so a floating input reads high.
void CycleControl::on_cyc_clk(sim::Level level) {
  const bool high = level != sim::Level::Low;
  if (high == cyc_clk_high_) return;
  cyc_clk_high_ = high;
  const bool active_edge = cycpol_.on(regs_) ? !high : high;
  if (!active_edge || !running_ || mode_ != Mode::MasterCycClk) return;
  recognise_at(time_base_.mclk().nth_edge_after(scheduler_.now(), kCycClkSyncEdges),
               &CycleControl::cyc_clk_action, true);
}

void CycleControl::cyc_clk_recognised() {
  if (!running_ || mode_ != Mode::MasterCycClk) return;
  window_.judge(true);
  master_cycle_start();
}

void CycleControl::master_cycle_start() {
  const Edge start = time_base_.mclk().first_at_or_after(scheduler_.now());
  time_base_.start_cycle(CycleKind::Master, [this](const CycleStart& s) { on_cycle_start(s); });
  cycle_ticks_ =
      DividerTicks::started_at(start, time_base_.tick_period(), time_base_.tick_period());
  // A cycle sends one MST: a new cycle start before TCYCSTART has passed drops it.
  const std::uint16_t delay = regs_.value(kTcycstart);
  if (delay == 0) {
    mst_send_.cancel();
    send_mst();
  } else {
    mst_send_.at_tick(cycle_ticks_, delay);
  }
  if (mode_ != Mode::MasterTimer) return;
  const std::uint16_t tscyc = time_base_.tscyc();
  if (tscyc == 0) {
    timer_idle_ = true;
    return;
  }
  next_cycle_.at_tick(cycle_ticks_, tscyc);
}

// The MST is due TCYCSTART after its cycle's start. A cycle sends at most one MST, and
// TCYCSTART >= TSCYC drops it (docs/timing.md): a next cycle start at this very instant
// comes first, whatever the order of the two equal-time events.
void CycleControl::mst_due() {
  if (master_cycle_starts_now()) return;
  send_mst();
}

bool CycleControl::master_cycle_starts_now() const {
  const sim::Time now = scheduler_.now();
  if (next_cycle_.pending() && next_cycle_.when() == now) return true;
  for (const Recognition& r : recognitions_) {
    if (r.cyc_clk && scheduler_.when(r.event) == now) return true;
  }
  return false;
}

void CycleControl::send_mst() {
  raise_cycst();
  for (std::size_t i = 0; i < send_mst_listeners_.size(); ++i) send_mst_listeners_[i]();
}

void CycleControl::on_divider_change(Edge edge, std::int64_t period) {
  cycle_ticks_.change_period(edge, period);
  next_cycle_.retime(cycle_ticks_, edge);
  mst_send_.retime(cycle_ticks_, edge);
}

}  // namespace sercon::chip

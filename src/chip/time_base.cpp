#include "sercon/chip/time_base.hpp"

#include <algorithm>
#include <stdexcept>
#include <utility>

#include "sercon/chip/chip.hpp"

namespace sercon::chip {
namespace {

constexpr std::uint8_t kClockDivider = 0x0E;
constexpr std::uint8_t kTscyc0 = 0x0F;
constexpr std::uint8_t kTscyc1 = 0x10;
constexpr std::uint8_t kTcnt = 0x12;
constexpr std::uint8_t kTcntst = 0x13;

}  // namespace

TimeBase::TimeBase(Chip& chip) : TimeBase(chip.scheduler(), chip.regs(), chip.mclk()) {}

TimeBase::TimeBase(sim::Scheduler& scheduler, RegisterFile& regs, sim::Time mclk_period)
    : TimeBase(scheduler, regs, MclkGrid::of_period(mclk_period)) {}

TimeBase::TimeBase(sim::Scheduler& scheduler, RegisterFile& regs, const MclkGrid& mclk)
    : scheduler_(scheduler),
      regs_(regs),
      mclk_(mclk),
      mclkdiv_(field_ref("MCLKDIV", regs.variant())),
      mclkst_(field_ref("MCLKST", regs.variant())),
      regmode_(field_ref("REGMODE", regs.variant())),
      phas0_(field_ref("PHAS0", regs.variant())),
      phasr_(field_ref("PHASR", regs.variant())) {
  regs_.on_read(kTcnt, [this](std::uint16_t) { return tcnt(); });
  regs_.on_change([this](std::uint8_t address) { on_register_change(address); });
}

TimeBase::~TimeBase() { cancel_all(); }

void TimeBase::cancel_all() {
  for (auto& pending : slots_) {
    if (pending->id == 0) continue;
    scheduler_.cancel(pending->event);
    release(*pending);
  }
}

TimeBase::Pending* TimeBase::find(CycleEvent id) const {
  const std::uint64_t index = id & ((std::uint64_t{1} << kIndexBits) - 1);
  if (index == 0 || index > slots_.size()) return nullptr;
  Pending* pending = slots_[index - 1].get();
  return pending->id == id ? pending : nullptr;
}

void TimeBase::release(Pending& pending) {
  const std::uint64_t index = pending.id & ((std::uint64_t{1} << kIndexBits) - 1);
  pending.id = 0;
  pending.action = nullptr;
  if (pending.callback) pending.callback = nullptr;  // what it captured goes now
  free_slots_.push_back(static_cast<std::uint32_t>(index - 1));
}

void TimeBase::reset(ResetCause) {
  running_ = false;
  cancel_all();
  divider_ = mclkdiv_.get(regs_);
  base_ = 0;
}

// Out of reset the counter runs from 0 on the free-running divider's grid; it is not a
// SERCOS cycle start, so no listener hears of it.
void TimeBase::release() {
  running_ = true;
  divider_ = mclkdiv_.get(regs_);
  const Edge start = mclk_.first_at_or_after(scheduler_.now());
  free_ = DividerTicks::started_at(start, tick_period(), tick_period());
  ticks_ = free_;
  base_ = 0;
}

std::int64_t TimeBase::count() const {
  if (!running_) return 0;
  return base_ + ticks_.count_through(now_edge());
}

std::uint16_t TimeBase::tscyc() const {
  const std::uint16_t phase_byte = regmode_.on(regs_) ? phas0_.get(regs_) : phasr_.get(regs_);
  return regs_.value((phase_byte & 0x07) <= 2 ? kTscyc0 : kTscyc1);
}

void TimeBase::start_cycle(CycleKind kind) {
  if (!running_) return;
  drop_future_events();
  const Edge start = mclk_.first_at_or_after(scheduler_.now());
  ticks_ = DividerTicks::started_at(start, mclkst_.get(regs_), tick_period());
  base_ = regs_.value(kTcntst);
  begin(kind);
}

void TimeBase::shift_cycle(std::int64_t by) {
  if (!running_) return;
  drop_future_events();
  base_ -= by;
  begin(CycleKind::Substitute);
}

void TimeBase::begin(CycleKind kind) {
  const CycleStart start{kind, count(), tscyc()};
  // Index loop: a listener may add listeners.
  for (std::size_t i = 0; i < cycle_listeners_.size(); ++i) cycle_listeners_[i](start);
}

// Events due exactly now belong to the step that has just happened in the old cycle and
// still run; later ones belonged to the old cycle and are dropped.
void TimeBase::drop_future_events() {
  const sim::Time now = scheduler_.now();
  for (auto& pending : slots_) {
    if (pending->id == 0 || pending->when <= now) continue;
    scheduler_.cancel(pending->event);
    release(*pending);
  }
}

TimeBase::Pending* TimeBase::claim(std::int64_t cycle_time) {
  if (!running_ || tick_of(cycle_time) <= ticks_.count_through(now_edge())) return nullptr;
  std::uint32_t index;
  if (!free_slots_.empty()) {
    index = free_slots_.back();
    free_slots_.pop_back();
  } else {
    if (slots_.size() + 1 >= (std::size_t{1} << kIndexBits)) {
      throw std::length_error("TimeBase: too many pending cycle-time events");
    }
    index = static_cast<std::uint32_t>(slots_.size());
    slots_.push_back(std::make_unique<Pending>());
    slots_.back()->owner = this;
  }
  Pending& pending = *slots_[index];
  pending.id = next_sequence_++ << kIndexBits | (index + 1u);
  pending.cycle_time = cycle_time;
  return &pending;
}

TimeBase::CycleEvent TimeBase::at_cycle_time(std::int64_t cycle_time,
                                             std::function<void()> callback) {
  Pending* pending = claim(cycle_time);
  if (pending == nullptr) return 0;
  pending->callback = std::move(callback);
  schedule(*pending);
  return pending->id;
}

TimeBase::CycleEvent TimeBase::at_cycle_time(std::int64_t cycle_time, sim::Scheduler::Action action,
                                             void* context) {
  Pending* pending = claim(cycle_time);
  if (pending == nullptr) return 0;
  pending->action = action;
  pending->context = context;
  schedule(*pending);
  return pending->id;
}

void TimeBase::schedule(Pending& pending) {
  pending.when = mclk_.time_of(ticks_.edge_of(tick_of(pending.cycle_time)));
  pending.event = scheduler_.at(pending.when, &TimeBase::fire, &pending);
}

// The slot is freed before the callback runs: the callback may ask for new events.
void TimeBase::fire(void* context) {
  auto& pending = *static_cast<Pending*>(context);
  if (pending.action != nullptr) {
    const sim::Scheduler::Action action = pending.action;
    void* const action_context = pending.context;
    pending.owner->release(pending);
    action(action_context);
    return;
  }
  auto callback = std::move(pending.callback);
  pending.owner->release(pending);
  callback();
}

void TimeBase::cancel(CycleEvent event) {
  Pending* pending = find(event);
  if (pending == nullptr) return;
  scheduler_.cancel(pending->event);
  release(*pending);
}

std::optional<sim::Time> TimeBase::when(CycleEvent event) const {
  const Pending* pending = find(event);
  if (pending == nullptr) return std::nullopt;
  return pending->when;
}

std::optional<sim::Time> TimeBase::time_of_cycle_time(std::int64_t cycle_time) const {
  if (!running_ || tick_of(cycle_time) <= ticks_.count_through(now_edge())) return std::nullopt;
  return mclk_.time_of(ticks_.edge_of(tick_of(cycle_time)));
}

void TimeBase::on_cycle_start(std::function<void(const CycleStart&)> listener) {
  cycle_listeners_.push_back(std::move(listener));
}

void TimeBase::on_divider_change(std::function<void(Edge, std::int64_t)> listener) {
  divider_listeners_.push_back(std::move(listener));
}

Edge TimeBase::free_tick_after(sim::Time t, std::int64_t n) const {
  return free_.edge_of(free_.count_through(mclk_.last_at_or_before(t)) + n);
}

// The dividers reload MCLKDIV at each tick: a new value counts from the tick after the
// pending one (DividerTicks::change_period), for every divider and every pending event.
void TimeBase::on_register_change(std::uint8_t address) {
  if (address != kClockDivider) return;
  const std::int64_t divider = mclkdiv_.get(regs_);
  if (divider == divider_) return;
  divider_ = divider;
  if (!running_) return;
  const Edge edge = mclk_.first_at_or_after(scheduler_.now());
  ticks_.change_period(edge, tick_period());
  free_.change_period(edge, tick_period());
  // Rescheduled in the order they were asked for (ids increase), so events that now
  // share a time run in that order.
  std::vector<Pending*> moved;
  for (auto& pending : slots_) {
    if (pending->id == 0 || pending->when <= mclk_.time_of(edge)) continue;  // tick before
    moved.push_back(pending.get());
  }
  std::sort(moved.begin(), moved.end(),
            [](const Pending* a, const Pending* b) { return a->id < b->id; });
  for (Pending* pending : moved) {
    scheduler_.cancel(pending->event);
    schedule(*pending);
  }
  for (auto& listener : divider_listeners_) listener(edge, tick_period());
}

}  // namespace sercon::chip

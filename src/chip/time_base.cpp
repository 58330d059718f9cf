#include "sercon/chip/time_base.hpp"

#include <algorithm>
#include <stdexcept>
#include <utility>

#include "sercon/chip/chip.hpp"

namespace sercon::chip {
namespace {

constexpr std::uint8_t kClockDivider = 0x0E;
constexpr std::uint8_t kTcnt = 0x12;

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
  read_fields();
  // Any register: the rare change costs a few loads; most changes are of other registers.
  regs_.on_change_first([this](std::uint8_t) { read_fields(); });
  regs_.on_read(kTcnt, [this](std::uint16_t) { return tcnt(); });
  regs_.on_change([this](std::uint8_t address) { on_register_change(address); });
}

void TimeBase::read_fields() {
  Fields& f = fields_;
  const std::uint16_t phase_byte = regmode_.on(regs_) ? phas0_.get(regs_) : phasr_.get(regs_);
  f.tscyc = regs_.field_value((phase_byte & 0x07) <= 2 ? kTscyc0Register : kTscyc1Register);
  f.mclkst = mclkst_.get(regs_);
  f.tcntst = regs_.field_value(kTcntstRegister);
}

TimeBase::~TimeBase() {
  cancel_all();
  for (OwnedEvent* owned : owned_) owned->time_base_ = nullptr;
}

// The action is given at each arm (at_cycle_time).
TimeBase::OwnedEvent::OwnedEvent(TimeBase& time_base, void* context)
    : time_base_(&time_base),
      scheduler_(time_base.scheduler_),
      slot_(scheduler_.own(nullptr, context)) {
  time_base.owned_.push_back(this);
}

TimeBase::OwnedEvent::~OwnedEvent() {
  scheduler_.disown(slot_);
  if (time_base_ != nullptr) std::erase(time_base_->owned_, this);
}

void TimeBase::cancel_all() {
  for (const Planned& planned : planned_) scheduler_.cancel(planned.event);
  planned_.clear();
  for (OwnedEvent* owned : owned_) scheduler_.cancel_owned(owned->slot_);
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
  ++cycles_;
  divider_ = mclkdiv_.get(regs_);
  const Edge start = mclk_.first_at_or_after(scheduler_.now());
  free_ = DividerTicks::started_at(start, tick_period(), tick_period());
  ticks_ = free_;
  base_ = 0;
}

// The other units' cycle-time events (TimeBase::drop_future_events).
void TimeBase::drop_future_planned(sim::Time now) {
  Planned* kept = planned_.data();
  for (const Planned& planned : planned_) {
    if (planned.when > now) {
      scheduler_.cancel(planned.event);
    } else if (planned.when == now && scheduler_.pending(planned.event)) {
      *kept++ = planned;
    }
  }
  planned_.erase(planned_.begin() + (kept - planned_.data()), planned_.end());
}

void TimeBase::prune() {
  std::erase_if(planned_,
                [this](const Planned& planned) { return !scheduler_.pending(planned.event); });
  planned_.reserve(std::max<std::size_t>(16, 2 * planned_.size()));
}

TimeBase::CycleEvent TimeBase::at_cycle_time(std::int64_t cycle_time,
                                             std::function<void()> callback) {
  const std::optional<sim::Time> step = step_ahead(cycle_time);
  if (!step) return {};
  if (planned_.size() == planned_.capacity()) prune();
  const sim::Scheduler::EventId event = scheduler_.at(*step, std::move(callback));
  planned_.push_back(Planned{event, cycle_time, *step});
  return event;
}

std::optional<sim::Time> TimeBase::time_of_cycle_time(std::int64_t cycle_time) const {
  return step_ahead(cycle_time);
}

TimeBase::CycleListenerId TimeBase::on_cycle_start(void* context, CycleListener listener) {
  if (starting_) throw std::logic_error("TimeBase::on_cycle_start: called during a cycle start");
  cycle_listeners_.push_back(CycleStartListener{listener, context});
  const CycleListenerId id = cycle_listeners_.size() - 1;
  set_cycle_listener_idle(id, false);
  return id;
}

void TimeBase::set_cycle_listener_idle(CycleListenerId id, bool idle) {
  cycle_listeners_[id].idle = idle;
  if (!idle) {
    if (active_.first == active_.end) {
      active_.first = id;
      active_.end = id + 1;
    } else {
      active_.first = std::min(active_.first, id);
      active_.end = std::max(active_.end, id + 1);
    }
    return;
  }
  while (active_.first != active_.end && cycle_listeners_[active_.first].idle) ++active_.first;
  while (active_.end != active_.first && cycle_listeners_[active_.end - 1].idle) --active_.end;
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
  // Lazily held events' times worked out on the grid they were held on.
  for (OwnedEvent* owned : owned_) scheduler_.settle_held(owned->slot_);
  const Edge edge = mclk_.first_at_or_after(scheduler_.now());
  ticks_.change_period(edge, tick_period());
  free_.change_period(edge, tick_period());
  // Moved in the order they were asked for (the scheduler's order of their scheduling: each
  // was scheduled when asked for, and a move keeps it), each after the events already due
  // at its new time, so events that now share a time run in that order.
  const sim::Time changed_at = mclk_.time_of(edge);
  struct Moved {
    sim::Scheduler::Generation generation;  // the order they were asked for
    sim::Scheduler::EventId event;          // 0: `owned` names an owned event
    const OwnedEvent* owned;
    std::int64_t cycle_time;
    sim::Time* when;
  };
  std::vector<Moved> moved;
  for (Planned& planned : planned_) {
    // Ran or cancelled, or due at the tick before the change: stays.
    if (planned.when <= changed_at || !scheduler_.pending(planned.event)) continue;
    moved.push_back(
        Moved{planned.event.generation, planned.event, nullptr, planned.cycle_time, &planned.when});
  }
  for (OwnedEvent* owned : owned_) {
    if (owned->when_ <= changed_at || !owned->pending()) continue;
    moved.push_back(Moved{
        scheduler_.owned_generation(owned->slot_), {}, owned, owned->cycle_time_, &owned->when_});
  }
  std::sort(moved.begin(), moved.end(),
            [](const Moved& a, const Moved& b) { return a.generation < b.generation; });
  for (const Moved& m : moved) {
    *m.when = time_of_step(m.cycle_time);
    if (m.owned != nullptr) {
      scheduler_.move_owned(m.owned->slot_, *m.when);
    } else {
      scheduler_.move(m.event, *m.when);
    }
  }
  for (auto& listener : divider_listeners_) listener(edge, tick_period());
}

}  // namespace sercon::chip

// The chip's µs time base and cycle counter (docs/timing.md, sections 1 "MCLK and the
// dividers" and 2 "The cycle counter TCNT").
//
// MCLKDIV divides MCLK into the µs tick: T_tick = (MCLKDIV + 1) / f_MCLK. The cycle
// counter (TCNT, 0x12) counts those ticks. At every cycle start it is loaded with TCNTST
// and its divider restarts from MCLKST: the first tick comes MCLKST MCLK periods later,
// then one every MCLKDIV + 1. The counter steps from c to c + 1 at "cycle time c": with
// the driver formulas (facts §5) that is c µs after the end of the MST, to within one
// MCLK period. Nothing is ticked: the counter is computed from the time when read, and
// only the events other units ask for (at_cycle_time) are scheduled.
//
// A second, free-running MCLKDIV divider (never restarted by cycle starts) times WDOGN.
#pragma once

#include <cassert>
#include <cstdint>
#include <functional>
#include <optional>
#include <vector>

#include "sercon/chip/chip_unit.hpp"
#include "sercon/chip/field_ref.hpp"
#include "sercon/chip/mclk_divider.hpp"
#include "sercon/chip/register_file.hpp"
#include "sercon/sim/scheduler.hpp"

namespace sercon::chip {

class Chip;

enum class CycleKind : std::uint8_t {
  Mst,         // slave: an MST was detected
  Substitute,  // slave: no MST in the window, the chip free-wheels (docs/timing.md)
  Master,      // master: cycle start from the internal timer or from CYC_CLK
};

struct CycleStart {
  CycleKind kind;
  std::int64_t count;   // counter value right after the start
  std::uint16_t tscyc;  // cycle time (µs) of the phase in force; 0 = not programmed
};

class TimeBase : public ChipUnit {
 public:
  // Registers the time base reads at a cycle start.
  static constexpr std::uint8_t kTscyc0Register = 0x0F;
  static constexpr std::uint8_t kTscyc1Register = 0x10;
  static constexpr std::uint8_t kTcntstRegister = 0x13;

  using CycleEvent = sim::Scheduler::EventId;  // CycleEvent{} names no event

  explicit TimeBase(Chip& chip);
  TimeBase(sim::Scheduler& scheduler, RegisterFile& regs, const MclkGrid& mclk);
  // An MCLK period of a whole number of picoseconds (MclkGrid::of_period).
  TimeBase(sim::Scheduler& scheduler, RegisterFile& regs, sim::Time mclk_period);
  // Cancels every pending cycle-time event, also those other units asked for.
  ~TimeBase() override;

  void reset(ResetCause cause) override;
  void release() override;

  sim::Scheduler& scheduler() const { return scheduler_; }
  RegisterFile& regs() const { return regs_; }
  const MclkGrid& mclk() const { return mclk_; }
  // MCLK periods per µs tick (MCLKDIV + 1) and the tick's nominal length in picoseconds
  // ((MCLKDIV + 1) * 1e12 / f_MCLK rounded down; the ticks themselves are on MCLK edges).
  std::int64_t tick_period() const { return divider_ + 1; }
  sim::Time tick_duration() const { return mclk_.time_of(tick_period()); }

  // The counter now, not wrapped (TCNT reads it modulo 2^16); 0 while held in reset.
  // Inline: a slave's window asks at every MST.
  std::int64_t count() const { return count_at(now_edge()); }
  // count() for `now_edge`, the last MCLK edge at or before now (a caller that knows it).
  std::int64_t count_at(Edge now_edge) const {
    if (!running_) return 0;
    return base_ + ticks_.count_through(now_edge);
  }
  std::uint16_t tcnt() const { return static_cast<std::uint16_t>(count() & 0xFFFF); }
  // TSCYC0 in phases 0..2, TSCYC1 in phases 3..7. The phase is PHAS0 (the byte a master
  // sends) in master mode and PHASR (the byte of the last MST received) in slave mode.
  // Inline: read at every cycle start (kept as data: read_fields()).
  std::uint16_t tscyc() const { return fields_.tscyc; }

  // A cycle starts now (called at an MCLK edge): the counter is loaded with TCNTST and
  // its divider restarts from MCLKST. Pending cycle-time events later than now are
  // dropped, then `first(start)` runs (the caller's own reaction: CycleControl's window,
  // ahead of every listener) and then the cycle-start listeners.
  // Inline (with `first`): a slave's cycle start is one step with CycleControl's MST.
  template <class First>
  [[gnu::always_inline]] void start_cycle(CycleKind kind, First first) {
    start_cycle_at(mclk_.first_at_or_after(scheduler_.now()), kind, first);
  }
  // start_cycle() for `start`, the first MCLK edge at or after now (a caller that knows it:
  // a slave's MST runs at its load edge).
  template <class First>
  [[gnu::always_inline]] void start_cycle_at(Edge start, CycleKind kind, First first) {
    if (!running_) return;
    drop_future_events();
    ticks_ = DividerTicks::started_at(start, fields_.mclkst, tick_period());
    base_ = fields_.tcntst;
    // The first tick is at least one edge after `start`, the first edge at or after now: the
    // counter holds TCNTST.
    begin(kind, base_, first);
  }
  // Substitute cycle (slave free-wheel): the counter moves back by `by` µs without a
  // divider restart, so the µs grid is kept; then as start_cycle.
  template <class First>
  void shift_cycle(std::int64_t by, First first) {
    if (!running_) return;
    drop_future_events();
    base_ -= by;
    begin(CycleKind::Substitute, count(), first);
  }

  // Calls `callback` when the counter steps from `cycle_time` to cycle_time + 1 in the
  // running cycle. Returns CycleEvent{} (nothing scheduled) when that step is not ahead.
  // Events are dropped by the next cycle start; listeners re-arm from on_cycle_start.
  CycleEvent at_cycle_time(std::int64_t cycle_time, std::function<void()> callback);
  // The same with `action(context)` (no std::function: for units that arm several
  // events per cycle). `context` must outlive the event.
  // Inline: a chip's lists and window arm a couple of dozen per cycle.
  [[gnu::always_inline]] CycleEvent at_cycle_time(std::int64_t cycle_time,
                                                  sim::Scheduler::Action action, void* context) {
    const std::optional<sim::Time> step = step_ahead(cycle_time);
    if (!step) return {};
    if (planned_.size() == planned_.capacity()) prune();
    const sim::Scheduler::EventId event = scheduler_.at(*step, action, context);
    planned_.push_back(Planned{event, cycle_time, *step});
    return event;
  }
  // A cycle-time event its owner keeps in place, for an owner with at most one pending at a
  // time that arms several a cycle (a list walk, the MST window): one owned scheduler slot
  // (no EventId, no free-list slot), armed without an entry in the time base's own record
  // to push and prune. Dropped at cycle starts, moved by MCLKDIV changes and cancelled at
  // reset as the others are, in the order all were asked for. Its actions get `context`.
  // Registered for the owner's lifetime: either may be destroyed first (the owner's
  // destruction cancels its event).
  class OwnedEvent {
   public:
    OwnedEvent(TimeBase& time_base, void* context);
    ~OwnedEvent();
    OwnedEvent(const OwnedEvent&) = delete;
    OwnedEvent& operator=(const OwnedEvent&) = delete;

    // Pending: armed, and it has not run, been cancelled or dropped since.
    bool pending() const { return scheduler_.owned_pending(slot_); }
    // When the event is due: meaningful only while it is pending (a cheap first test before
    // asking the scheduler whether it is). Not for one held (hold_at_cycle_time) until its
    // time is worked out.
    sim::Time when() const { return when_; }
    void cancel() { scheduler_.cancel_owned(slot_); }  // if pending

   private:
    friend class TimeBase;
    TimeBase* time_base_;  // null once the time base is gone
    sim::Scheduler& scheduler_;
    sim::Scheduler::OwnedSlot slot_;
    std::int64_t cycle_time_ = 0;
    sim::Time when_ = 0;     // kept up to date while pending (held lazily: now at the hold)
    sim::Time held_at_ = 0;  // when it was held lazily, and in which cycle (cycles_)
    std::uint64_t held_cycle_ = 0;
  };
  // at_cycle_time() into `owned` (whose earlier event has run or was cancelled), with its
  // context. False (and no event) when the step is not ahead.
  [[gnu::always_inline]] bool at_cycle_time(OwnedEvent& owned, std::int64_t cycle_time,
                                            sim::Scheduler::Action action) {
    return owned_at_cycle_time(owned, cycle_time, [&](sim::Time when) {
      scheduler_.arm_owned_idle(owned.slot_, when, action);
    });
  }
  // The same, deferred (Scheduler::defer_owned): for an event mostly dropped by the next
  // cycle start long before it is due (the slave's window close), which then never enters
  // the scheduler's queue.
  [[gnu::always_inline]] bool defer_at_cycle_time(OwnedEvent& owned, std::int64_t cycle_time,
                                                  sim::Scheduler::Action action) {
    return owned_at_cycle_time(owned, cycle_time, [&](sim::Time when) {
      scheduler_.defer_owned(owned.slot_, when, action);
    });
  }
  // defer_at_cycle_time() from a cycle start's `first` after a divider restart (start_cycle,
  // start_cycle_at), for a `cycle_time` not below the counter (TCNTST), into an `owned` the
  // start left idle: the step's tick then comes after the restart's edge, itself at or after
  // now, so it is ahead; neither is tested (asserted in debug builds). Inline: a slave's window
  // close at every MST.
  [[gnu::always_inline]] void defer_after_restart(OwnedEvent& owned, std::int64_t cycle_time,
                                                  sim::Scheduler::Action action) {
    const sim::Time when = time_of_step(cycle_time);
    assert(cycle_time >= base_ && step_ahead(cycle_time) == when);
    scheduler_.defer_idle_owned(owned.slot_, when, action);
    owned.cycle_time_ = cycle_time;
    owned.when_ = when;
  }
  // The same, held (Scheduler::hold_owned_lazily): for an event whose action would change
  // nothing (INT_ENDMK raised while latched); the owner calls queue_held() when that may
  // change. Its time is worked out only when something asks, by `resolve`, which gives
  // resolve_held(owned) (the owner's function of the slot's context). Not scheduled when the
  // step is not ahead, as at_cycle_time(); the owner is not told so (its late handling
  // would change nothing either). As at_cycle_time(), `owned`'s earlier event has run or was
  // cancelled.
  [[gnu::always_inline]] void hold_at_cycle_time(OwnedEvent& owned, std::int64_t cycle_time,
                                                 sim::Scheduler::Action action,
                                                 sim::Scheduler::Resolve resolve) {
    scheduler_.hold_idle_owned_lazily(owned.slot_, action, resolve);
    owned.cycle_time_ = cycle_time;
    const sim::Time now = scheduler_.now();
    owned.when_ = now;  // not known yet: taken as now, so the next cycle start leaves it
    owned.held_at_ = now;
    owned.held_cycle_ = cycles_;
  }
  // A held event's time: its step's as at_cycle_time() would have found it when it was
  // held, or Scheduler::kUnheld if the step was not ahead then, or a cycle started
  // since (which would have dropped it or found it passed: either way it never runs). The
  // grid is the hold's: an MCLKDIV change settles the event first. One case differs: a step
  // exactly at the next cycle's start, held after that start was scheduled, would still have
  // run at it had its flag been cleared there. The owner must cancel its held event at every
  // cycle start (the telegram list's start() does), so the case never arises.
  sim::Time resolve_held(OwnedEvent& owned) const {
    if (owned.held_cycle_ != cycles_) return sim::Scheduler::kUnheld;
    const std::optional<sim::Time> step = step_after(owned.cycle_time_, owned.held_at_);
    if (!step) return sim::Scheduler::kUnheld;
    owned.when_ = *step;
    return *step;
  }
  void queue_held(OwnedEvent& owned) { scheduler_.queue_held(owned.slot_); }
  void cancel(CycleEvent event) { scheduler_.cancel(event); }
  // When a pending event will run; nullopt once it ran, was cancelled or dropped.
  std::optional<sim::Time> when(CycleEvent event) const { return scheduler_.when(event); }
  // When the step out of `cycle_time` will happen in the running cycle, if it is ahead.
  std::optional<sim::Time> time_of_cycle_time(std::int64_t cycle_time) const;
  // When the step out of `cycle_time` happened in the running cycle, if it has (at or
  // before now). nullopt when it is ahead, or was not in this cycle (before the cycle
  // start) or came before the last MCLKDIV change (its time is not kept).
  std::optional<sim::Time> time_of_past_cycle_time(std::int64_t cycle_time) const {
    const std::int64_t tick = tick_of(cycle_time);
    if (!running_ || tick <= ticks_.ticks_before_change()) return std::nullopt;
    const sim::Time when = time_of_step(cycle_time);
    if (when > scheduler_.now()) return std::nullopt;
    return when;
  }

  // `listener(context, start)` at every cycle start, in the order registered. A function
  // and a context, not a std::function: the listeners are the chip's units, fixed at
  // construction, and run at every cycle start of every chip. std::logic_error when called
  // from a listener during a cycle start.
  using CycleListener = void (*)(void* context, const CycleStart& start);
  using CycleListenerId = std::size_t;
  CycleListenerId on_cycle_start(void* context, CycleListener listener);
  // A listener whose cycle start would change nothing in its present state (CON_CLK and
  // DIV_CLK unused, the usual case) is not called while it says so; it must say otherwise
  // the moment that may change (a register write, say), also during a cycle start.
  void set_cycle_listener_idle(CycleListenerId id, bool idle);
  // MCLKDIV changed, registered at MCLK edge `edge`; `period` is the new MCLKDIV + 1.
  void on_divider_change(std::function<void(Edge edge, std::int64_t period)> listener);

  // Edge of the n-th tick (n >= 1) of the free-running divider strictly after `t`.
  Edge free_tick_after(sim::Time t, std::int64_t n) const;

 private:
  // A cycle-time event is a scheduler event: its id is the scheduler's EventId, never
  // reused (nor are generations), so a stale id never matches. `planned_` keeps
  // them in the order they were asked for, to drop, move or cancel them; entries of
  // events that ran or were cancelled are pruned from time to time.
  struct Planned {
    sim::Scheduler::EventId event;
    std::int64_t cycle_time;
    sim::Time when;  // kept up to date while pending
  };
  // The owned forms' one body: `place(when)` puts the event in the scheduler (armed,
  // deferred or held), then `owned` notes what was asked.
  template <typename Place>
  [[gnu::always_inline]] bool owned_at_cycle_time(OwnedEvent& owned, std::int64_t cycle_time,
                                                  Place place) {
    const std::optional<sim::Time> step = step_ahead(cycle_time);
    if (!step) return false;
    place(*step);
    owned.cycle_time_ = cycle_time;
    owned.when_ = *step;
    return true;
  }
  // When the step out of `cycle_time` happens if it is ahead, else nullopt. A tick is ahead
  // when it comes after the last period change (earlier ones have passed) and its edge is
  // after now (after the last edge at or before now): one edge time, no tick count.
  [[gnu::always_inline]] std::optional<sim::Time> step_ahead(std::int64_t cycle_time) const {
    return step_after(cycle_time, scheduler_.now());
  }
  // step_ahead() as it was at `now` (a lazily held event's hold: resolve_held()).
  std::optional<sim::Time> step_after(std::int64_t cycle_time, sim::Time now) const {
    const std::int64_t tick = tick_of(cycle_time);
    if (!running_ || tick <= ticks_.ticks_before_change()) return std::nullopt;
    const sim::Time when = mclk_.time_of(ticks_.edge_of(tick));
    if (when <= now) return std::nullopt;
    return when;
  }
  sim::Time time_of_step(std::int64_t cycle_time) const {
    return mclk_.time_of(ticks_.edge_of(tick_of(cycle_time)));
  }
  Edge now_edge() const { return mclk_.last_at_or_before(scheduler_.now()); }
  std::int64_t tick_of(std::int64_t cycle_time) const { return cycle_time + 1 - base_; }
  // planned_ is full: drops the entries of events that ran or were cancelled, and makes
  // room for as many again as are left.
  void prune();
  // Events due exactly now belong to the step that has just happened in the old cycle and
  // still run; later ones belonged to the old cycle and are dropped. Earlier ones have run
  // or were cancelled.
  [[gnu::always_inline]] void drop_future_events() {
    ++cycles_;  // lazily held events: resolve_held() finds them over
    const sim::Time now = scheduler_.now();
    if (!planned_.empty()) drop_future_planned(now);
    // An owned event due now stays as well (cancelling one that ran or was cancelled does nothing).
    for (const OwnedEvent* owned : owned_) {
      if (owned->when_ > now) scheduler_.cancel_owned(owned->slot_);
    }
  }
  void drop_future_planned(sim::Time now);
  void cancel_all();
  // `first(start)`, then the listeners; `count`: the counter now.
  template <class First>
  [[gnu::always_inline]] void begin(CycleKind kind, std::int64_t count, First first) {
    const CycleStart start{kind, count, tscyc()};
    // A range loop (the listeners' vector reloaded after every call cost about 25 a start):
    // on_cycle_start() refuses to add a listener meanwhile.
    struct Starting {
      bool& flag;
      explicit Starting(bool& f) : flag(f) { flag = true; }
      ~Starting() { flag = false; }
    } starting{starting_};
    first(start);
    // The listeners from the first not idle to the last (active_), mostly one (the telegram
    // processor's, after the idle CON_CLK and DIV_CLK). A listener may wake or idle one during
    // the start: the end is read again, as is each one's idle flag at its turn (the ones before
    // the first have had their turn).
    const CycleStartListener* const listeners = cycle_listeners_.data();
    for (std::size_t i = active_.first; i < active_.end; ++i) {
      const CycleStartListener& l = listeners[i];
      if (!l.idle) l.listener(l.context, start);
    }
  }
  void on_register_change(std::uint8_t address);
  void read_fields();

  sim::Scheduler& scheduler_;
  RegisterFile& regs_;
  MclkGrid mclk_;
  FieldRef mclkdiv_, mclkst_, regmode_, phas0_, phasr_;
  // The register fields a cycle start reads, kept as data: read again at every register value
  // change by a listener that runs before all others (RegisterFile::on_change_first), so
  // whatever a listener runs sees them current. In a steady ring no value changes.
  struct Fields {
    std::uint16_t tscyc = 0;   // tscyc()
    std::uint16_t mclkst = 0;  // MCLKST
    std::uint16_t tcntst = 0;  // TCNTST
  } fields_;
  bool running_ = false;
  std::uint64_t cycles_ = 0;  // cycles ended (drop_future_events) and releases
  std::int64_t divider_ = 0;  // MCLKDIV in force
  std::int64_t base_ = 0;     // counter value before the first tick of ticks_
  DividerTicks ticks_;        // the cycle counter's divider
  DividerTicks free_;         // the free-running divider
  std::vector<Planned> planned_;
  std::vector<OwnedEvent*> owned_;  // the registered OwnedEvents, alive
  struct CycleStartListener {
    CycleListener listener;
    void* context;
    bool idle = false;
  };
  std::vector<CycleStartListener> cycle_listeners_;
  struct {
    std::size_t first = 0, end = 0;  // no listener outside [first, end) is called (idle)
  } active_;
  bool starting_ = false;  // the cycle-start listeners run
  std::vector<std::function<void(Edge, std::int64_t)>> divider_listeners_;
};

}  // namespace sercon::chip

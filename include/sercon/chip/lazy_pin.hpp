// An output pin whose level its unit can compute for any time (RECACTN from the telegrams
// the receiver has been told of, IDLE from the transmitter's own telegrams) instead of
// switching it by an event at every change: a ring of 9 chips would spend two events per
// telegram per chip on pins nobody looks at. Reading the pin asks the unit; only while
// someone watches the pin are its changes scheduled as events (one pending at a time), so
// waveforms still see every edge at its exact time.
#pragma once

#include "sercon/chip/pins.hpp"
#include "sercon/sim/scheduler.hpp"
#include "sercon/sim/signal.hpp"
#include "sercon/sim/time.hpp"

namespace sercon::chip {

class Chip;

class LazyPin {
 public:
  // The unit's side: the logical level (true = high) at time `t` >= now, and the first time
  // after `t` at which it changes (kNever when it stays as it is).
  class Source {
   public:
    virtual ~Source() = default;
    virtual bool level_at(sim::Time t) const = 0;
    virtual sim::Time next_change_after(sim::Time t) const = 0;
  };
  static constexpr sim::Time kNever = INT64_MAX;

  LazyPin(Chip& chip, Pin pin, const Source& source);
  ~LazyPin();
  LazyPin(const LazyPin&) = delete;
  LazyPin& operator=(const LazyPin&) = delete;

  // What the unit will do from now on changed (a telegram announced, superseded, reset):
  // while the pin is watched, bring it up to date and schedule its next change.
  // Inline, as idle(): at every telegram a node is told of, and the pin is mostly unwatched.
  void replan() {
    if (!idle()) plan(false);
  }
  // Nobody watches the pin and no change is planned: replan() would do nothing.
  // The signal is asked only once it has had a watcher: a lazy hop asks at every node, and
  // the pin's signal is another object to load.
  bool idle() const { return event_.generation == 0 && !(had_watcher_ && signal_.watched()); }

 private:
  static sim::Level provide(const void* self);
  void plan(bool watcher_coming);
  void changed();  // the scheduled change is due

  Chip& chip_;
  Pin pin_;
  sim::Signal& signal_;  // chip_.pin(pin_)
  const Source& source_;
  sim::Scheduler::EventId event_{};
  bool had_watcher_;  // signal_.watch() has been called (only it makes signal_.watched() true)
};

}  // namespace sercon::chip

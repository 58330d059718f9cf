// A named wire between models (a chip pin, a fibre's light level). Watchers hear every
// change of level; reading the time of a change is the scheduler's job.
//
// Two kinds of listeners. A model's reactions (react(): a chip taking its input pins) run
// at once at every change, depth first, as the hardware would. Watchers (watch(): tests,
// boards, the C API's pin callbacks) hear changes one at a time, in the order they happened,
// when the step that made them is done: a change made inside a reaction, a watcher or a
// batch (a scheduler event, a chip's bus access) takes effect at once, but its watchers are
// told after the watchers of the change being told, or when the batch ends. So a model
// finishes its reaction before anyone hears what it did, and a callback that drives another
// pin never runs inside a half-done one.
//
// A signal may have a provider: a function its model uses to compute the level when it is
// read, so that a pin nobody watches costs no event per change (RECACTN, IDLE: one change
// per telegram on every node). The model keeps the watched signal up to date with set() as
// usual; on_watch tells it when the first watcher arrives.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <type_traits>
#include <vector>

namespace sercon::sim {

enum class Level : std::uint8_t { Low = 0, High = 1, HighZ = 2 };

constexpr Level level_of(bool high) { return high ? Level::High : Level::Low; }
constexpr char level_char(Level level) {
  return level == Level::Low ? '0' : level == Level::High ? '1' : 'z';
}

class Signal {
 public:
  using Watcher = std::function<void(Level)>;
  using Provider = Level (*)(const void* context);

  explicit Signal(std::string name, Level initial = Level::Low)
      : name_(std::move(name)), level_(initial) {}
  ~Signal();
  Signal(Signal&&) = default;
  Signal& operator=(Signal&&) = default;

  const std::string& name() const { return name_; }
  Level level() const { return provider_ ? provider_(provider_context_) : level_; }
  bool high() const { return level() == Level::High; }

  // Changes the level and tells every watcher (after those of a change being told, see
  // above); setting the same level again is silent.
  void set(Level level);
  void set(bool high) { set(level_of(high)); }
  // Runs `f`; the changes it makes (on any signal) are told when it returns, in order, as
  // if they were made inside a change being told. For a model's whole reaction to
  // something that is no pin (a scheduler event, a register access): nobody hears its
  // outputs half-way through it. Nested inside a change or another batch, it is part of it.
  template <typename F>
  static decltype(auto) batch(F&& f);
  // batch() for each of a run of steps (Scheduler::run_until: one per event), the batch
  // kept open from one step to the next: after each step, done() tells what it changed,
  // as the end of its own batch would. Nested inside a change or another batch, the steps
  // are part of it. An exception drops what is pending, as batch() does.
  class Steps {
   public:
    Steps() : outer_(open_batch()) {}
    ~Steps() {
      if (outer_) abandon_batch();
    }
    Steps(const Steps&) = delete;
    Steps& operator=(const Steps&) = delete;
    void done() {
      // any_pending_ first: mostly false, and the compiler keeps the order of the tests.
      if (any_pending_ && outer_) {
        tell_pending();   // closes the batch
        telling_ = true;  // and the next step's opens
      }
    }

   private:
    bool outer_;
  };

  // Returns a handle for unwatch(). The on_watch hook runs first (the new watcher does not
  // hear the model bringing the level up to date).
  std::size_t watch(Watcher watcher);
  // A model's own reaction to this signal (a chip taking its input pins): run at once at
  // every change, before any watcher hears it, and the changes it makes are heard after it
  // is done. Not counted by watched(); kept for the signal's life.
  void react(Watcher reaction);
  void unwatch(std::size_t handle);
  // Inline and without touching the watchers: asked at every telegram that passes a chip.
  bool watched() const { return watching_ != 0; }

  // level() asks `provider(context)` from now on; nullptr goes back to the stored level.
  void provide(Provider provider, const void* context);
  void on_watch(std::function<void()> hook) { on_watch_ = std::move(hook); }

 private:
  // Inline, with the two flags they test: every scheduler event opens and closes a batch,
  // and nearly every one changes nothing anyone watches.
  static bool open_batch() {  // true: this call opened it (nothing was being told)
    if (telling_) return false;
    telling_ = true;
    return true;
  }
  // Tells what is pending, in order, then closes.
  static void close_batch() {
    if (!any_pending_) {  // the usual event: its pins changed nothing anyone watches
      telling_ = false;
      return;
    }
    tell_pending();
  }
  static void tell_pending();   // close_batch() with changes pending
  static void abandon_batch();  // an exception: nothing left pending, closed
  void tell(Level level);
  std::string name_;
  Level level_;
  std::vector<Watcher> watchers_;  // unwatched slots hold an empty function
  std::vector<Watcher> reactions_;
  std::size_t watching_ = 0;  // non-empty slots
  Provider provider_ = nullptr;
  const void* provider_context_ = nullptr;
  std::function<void()> on_watch_;
  // One simulation runs on one thread. any_pending_: changes wait in the pending list
  // (signal.cpp), asked without touching that vector.
  static inline thread_local bool telling_ = false;
  static inline thread_local bool any_pending_ = false;
};

template <typename F>
decltype(auto) Signal::batch(F&& f) {
  if (!open_batch()) return f();
  struct Abandon {
    bool armed = true;
    ~Abandon() {
      if (armed) abandon_batch();
    }
  } abandon;
  if constexpr (std::is_void_v<decltype(f())>) {
    f();
    abandon.armed = false;
    close_batch();
  } else {
    auto result = f();
    abandon.armed = false;
    close_batch();
    return result;
  }
}

}  // namespace sercon::sim

// A named wire between models (a chip pin, a fibre's light level). Watchers hear every
// change of level; reading the time of a change is the scheduler's job.
//
// A signal may have a provider: a function its model uses to compute the level when it is
// read, so that a pin nobody watches costs no event per change (RECACTN, IDLE: one change
// per telegram on every node). The model keeps the watched signal up to date with set() as
// usual; on_watch tells it when the first watcher arrives.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
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

  const std::string& name() const { return name_; }
  Level level() const { return provider_ ? provider_(provider_context_) : level_; }
  bool high() const { return level() == Level::High; }

  // Changes the level and tells every watcher; setting the same level again is silent.
  void set(Level level);
  void set(bool high) { set(level_of(high)); }

  // Returns a handle for unwatch(). The on_watch hook runs first (the new watcher does not
  // hear the model bringing the level up to date).
  std::size_t watch(Watcher watcher);
  void unwatch(std::size_t handle);
  // Inline and without touching the watchers: asked at every telegram that passes a chip.
  bool watched() const { return watching_ != 0; }

  // level() asks `provider(context)` from now on; nullptr goes back to the stored level.
  void provide(Provider provider, const void* context);
  void on_watch(std::function<void()> hook) { on_watch_ = std::move(hook); }

 private:
  std::string name_;
  Level level_;
  std::vector<Watcher> watchers_;  // unwatched slots hold an empty function
  std::size_t watching_ = 0;       // non-empty slots
  Provider provider_ = nullptr;
  const void* provider_context_ = nullptr;
  std::function<void()> on_watch_;
};

}  // namespace sercon::sim

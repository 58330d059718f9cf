// A named wire between models (a chip pin, a fibre's light level). Watchers hear every
// change of level; reading the time of a change is the scheduler's job.
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

  explicit Signal(std::string name, Level initial = Level::Low)
      : name_(std::move(name)), level_(initial) {}

  const std::string& name() const { return name_; }
  Level level() const { return level_; }
  bool high() const { return level_ == Level::High; }

  // Changes the level and tells every watcher; setting the same level again is silent.
  void set(Level level);
  void set(bool high) { set(level_of(high)); }

  // Returns a handle for unwatch().
  std::size_t watch(Watcher watcher);
  void unwatch(std::size_t handle);

 private:
  std::string name_;
  Level level_;
  std::vector<Watcher> watchers_;  // unwatched slots hold an empty function
};

}  // namespace sercon::sim

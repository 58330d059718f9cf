#include "sercon/sim/signal.hpp"

namespace sercon::sim {

void Signal::set(Level level) {
  if (level == level_) return;
  level_ = level;
  // Index loop: a watcher may add watchers while being told.
  for (std::size_t i = 0; i < watchers_.size(); ++i) {
    if (watchers_[i]) watchers_[i](level);
  }
}

std::size_t Signal::watch(Watcher watcher) {
  if (on_watch_) on_watch_();
  if (watcher) ++watching_;
  watchers_.push_back(std::move(watcher));
  return watchers_.size() - 1;
}

void Signal::unwatch(std::size_t handle) {
  if (handle >= watchers_.size() || !watchers_[handle]) return;
  watchers_[handle] = nullptr;
  --watching_;
}

void Signal::provide(Provider provider, const void* context) {
  provider_ = provider;
  provider_context_ = context;
}

}  // namespace sercon::sim

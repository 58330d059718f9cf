#include "sercon/sim/signal.hpp"

namespace sercon::sim {
namespace {

// Changes waiting to be told while watchers of another are being told (one simulation runs
// on one thread).
struct Pending {
  Signal* signal;
  Level level;
};
thread_local std::vector<Pending> pending;

}  // namespace

// A signal gone before its turn is skipped (left in place: the drain walks by index).
Signal::~Signal() {
  if (!any_pending_) return;
  for (Pending& p : pending) {
    if (p.signal == this) p.signal = nullptr;
  }
}

void Signal::set(Level level) {
  if (level == level_) return;
  level_ = level;
  if (watching_ == 0 && reactions_.empty()) return;
  // This change is heard before the changes its reactions make; all of them when the
  // outermost step is done.
  batch([this, level] {
    if (watching_ != 0) {
      pending.push_back(Pending{this, level});
      any_pending_ = true;
    }
    for (std::size_t i = 0; i < reactions_.size(); ++i) reactions_[i](level);
  });
}

void Signal::react(Watcher reaction) { reactions_.push_back(std::move(reaction)); }

void Signal::tell_pending() {
  // Closed however it ends: a watcher that throws leaves nothing queued for the next change.
  struct Done {
    ~Done() { abandon_batch(); }
  } done;
  for (std::size_t i = 0; i < pending.size(); ++i) {
    const Pending p = pending[i];
    if (p.signal != nullptr) p.signal->tell(p.level);
  }
}

void Signal::abandon_batch() {
  telling_ = false;
  if (!any_pending_) return;
  any_pending_ = false;
  pending.clear();
}

void Signal::tell(Level level) {
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

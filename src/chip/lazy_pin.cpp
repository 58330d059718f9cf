#include "sercon/chip/lazy_pin.hpp"

#include "sercon/chip/chip.hpp"

namespace sercon::chip {

LazyPin::LazyPin(Chip& chip, Pin pin, const Source& source)
    : chip_(chip),
      pin_(pin),
      signal_(chip.pin(pin)),
      source_(source),
      had_watcher_(signal_.watched()) {
  signal_.provide(&LazyPin::provide, this);
  signal_.on_watch([this] {
    had_watcher_ = true;
    plan(true);
  });
}

LazyPin::~LazyPin() {
  chip_.scheduler().cancel(event_);
  signal_.provide(nullptr, nullptr);
  signal_.on_watch(nullptr);
}

// Datasheet Table 1: OUTZ = 1 puts every output into high impedance.
sim::Level LazyPin::provide(const void* self) {
  const auto& pin = *static_cast<const LazyPin*>(self);
  if (pin.chip_.outputs_off()) return sim::Level::HighZ;
  return sim::level_of(pin.source_.level_at(pin.chip_.scheduler().now()));
}

// `watcher_coming`: the first watcher is being added (Signal::watch tells us before it
// joins, so it does not hear the level brought up to date).
void LazyPin::plan(bool watcher_coming) {
  sim::Scheduler& s = chip_.scheduler();
  s.cancel(event_);
  event_ = {};
  if (!watcher_coming && !signal_.watched()) return;
  const sim::Time now = s.now();
  chip_.set_output(pin_, source_.level_at(now));
  const sim::Time next = source_.next_change_after(now);
  if (next == kNever) return;
  event_ = s.at(
      next, [](void* self) { static_cast<LazyPin*>(self)->changed(); }, this);
}

void LazyPin::changed() {
  event_ = {};
  replan();
}

}  // namespace sercon::chip

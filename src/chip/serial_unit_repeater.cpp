#include "sercon/chip/serial_unit_repeater.hpp"

#include <algorithm>

#include "sercon/chip/chip.hpp"
#include "sercon/chip/serial_unit.hpp"
#include "sercon/chip/serial_unit_fields.hpp"
#include "sercon/chip/serial_unit_outputs.hpp"
#include "sercon/chip/serial_unit_receiver.hpp"

namespace sercon::chip {

void SerialRepeater::cancel() {
  for (const Pending& p : pending_) unit_.chip().scheduler().cancel(p.event);
  pending_.clear();
}

void SerialRepeater::reset() {
  cancel();
  repon_ = false;
  own_active_ = false;
  last_forward_ = 0;
  unit_.outputs().line_condition(LineCondition::Dark, 0);
}

void SerialRepeater::release() {
  repon_ = unit_.fields().repon.on(unit_.chip().regs());
  forwarded_ = unit_.receiver().input();
  show_line();
}

sim::Time SerialRepeater::forward_time(sim::Time t) const {
  const sim::Time sclk = sim::period_of_hz(unit_.chip().config().sclk_hz);
  const sim::Time due = t + SerialUnit::kRepeaterDelayBits * unit_.bit_period();
  return (due + sclk - 1) / sclk * sclk;
}

void SerialRepeater::input(const RxdSegment& segment) {
  if (!repon_ || unit_.bit_period() == 0) return;
  // Times stay in order even if the delay shrinks (a faster rate chosen meanwhile).
  const sim::Time at = std::max(forward_time(segment.since), last_forward_);
  last_forward_ = at;
  pending_.push_back(Pending{segment, {}});
  pending_.back().segment.since = at;
  // The callback holds `this` only (no allocation); the segment waits in pending_.
  pending_.back().event = unit_.chip().scheduler().at(at, [this] { forward(); });
}

void SerialRepeater::forward() {
  forwarded_ = std::move(pending_.front().segment);
  pending_.pop_front();
  const RxdSegment& segment = forwarded_;
  if (own_active_) return;  // own telegram wins; a burst starting under it is lost whole
  if (segment.is_burst) {
    unit_.outputs().line_burst(segment.burst());
  } else {
    unit_.outputs().line_condition(segment.condition, segment.period);
  }
}

void SerialRepeater::own_begin(const LineBurst& burst) {
  own_active_ = true;
  unit_.outputs().line_burst(burst);  // cuts a repeated telegram in the way
}

void SerialRepeater::own_end() {
  own_active_ = false;
  if (repon_) show_line();  // otherwise the own idle fill follows, as the burst implies
}

void SerialRepeater::refresh() {
  const bool on = unit_.fields().repon.on(unit_.chip().regs());
  if (on != repon_) {
    repon_ = on;
    cancel();
    // Switched on: the line takes up what RxD carries now (a telegram half-way through is
    // not picked up; its rest would decode to nothing).
    if (on) forwarded_ = unit_.receiver().input();
    if (!own_active_) show_line();
  } else if (!repon_ && !own_active_) {
    show_line();  // the own idle fill at a new bit rate; a repeated telegram is left alone
  }
}

void SerialRepeater::show_line() {
  if (own_active_) return;
  if (repon_) {
    unit_.outputs().line_condition(forwarded_.condition_at_join(), forwarded_.period);
  } else {
    unit_.outputs().line_condition(LineCondition::Idle, unit_.bit_period());
  }
}

}  // namespace sercon::chip

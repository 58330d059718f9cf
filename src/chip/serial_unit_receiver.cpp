#include "sercon/chip/serial_unit_receiver.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "sercon/chip/chip.hpp"
#include "sercon/chip/serial_unit_fields.hpp"
#include "sercon/chip/serial_unit_monitor.hpp"
#include "sercon/chip/serial_unit_repeater.hpp"

namespace sercon::chip {

SerialReceiver::~SerialReceiver() {
  cancel_chip_events();
  for (const auto id : deferred_) unit_.chip().scheduler().cancel(id);
}

void SerialReceiver::cancel_chip_events() {
  sim::Scheduler& s = unit_.chip().scheduler();
  for (const Report& r : reports_) s.cancel(r.event);
  s.cancel(recact_event_);
  current_ = Current{};
  reports_.clear();
  free_reports_.clear();
}

std::size_t SerialReceiver::schedule_report(sim::Time when, Report report) {
  std::size_t slot = reports_.size();
  if (free_reports_.empty()) {
    reports_.push_back(std::move(report));
  } else {
    slot = free_reports_.back();
    free_reports_.pop_back();
    reports_[slot] = std::move(report);
  }
  reports_[slot].event = unit_.chip().scheduler().at(when, [this, slot] { fire(slot); });
  return slot;
}

void SerialReceiver::cancel_report(std::size_t slot, sim::Scheduler::EventId event) {
  if (slot == kNone || !unit_.chip().scheduler().cancel(event)) return;
  reports_[slot] = Report{};
  free_reports_.push_back(slot);
}

void SerialReceiver::fire(std::size_t slot) {
  const Report r = std::move(reports_[slot]);
  reports_[slot] = Report{};
  free_reports_.push_back(slot);
  const wire::DecodedFrame& f = r.decode->frames[r.frame];
  if (r.telegram) {
    on_telegram_(ReceivedTelegram{r.start, r.end, r.detected, f});
  } else {
    on_start_(r.start, f.address);
  }
}

void SerialReceiver::reset() {
  cancel_chip_events();
  recact_ = false;  // the register reset cleared RECACT, the chip's reset RECACTN
}

void SerialReceiver::release() {}

void SerialReceiver::check_order(sim::Time at) {
  const sim::Time now = unit_.chip().scheduler().now();
  if (at < now) {
    throw std::invalid_argument("RxD: a change at " + std::to_string(at) + " ps is before now (" +
                                std::to_string(now) + " ps)");
  }
  if (at < last_change_) {
    throw std::invalid_argument("RxD: a change at " + std::to_string(at) +
                                " ps comes after one at " + std::to_string(last_change_) +
                                " ps (changes must come in time order)");
  }
  last_change_ = at;
}

void SerialReceiver::line_condition(sim::Time at, LineCondition condition, sim::Time bit_period) {
  const bool toggles = condition == LineCondition::Idle || condition == LineCondition::ZeroBits;
  if (toggles ? bit_period <= 0 : bit_period < 0) {
    throw std::invalid_argument("RxD: " + std::string(to_string(condition)) + " with bit period " +
                                std::to_string(bit_period) + " ps");
  }
  check_order(at);
  const RxdSegment segment = RxdSegment::of(at, condition, toggles ? bit_period : 0);
  if (at == unit_.chip().scheduler().now()) return take(segment);
  deferred_.push_back(unit_.chip().scheduler().at(at, [this, segment] {
    deferred_.pop_front();
    take(segment);
  }));
}

void SerialReceiver::line_burst(const LineBurst& burst) {
  if (!burst.bits) throw std::invalid_argument("RxD: a burst without bits");
  if (burst.bit_period <= 0) {
    throw std::invalid_argument("RxD: a burst with bit period " + std::to_string(burst.bit_period) +
                                " ps");
  }
  check_order(burst.start);
  const RxdSegment segment = RxdSegment::of(burst);
  if (burst.start == unit_.chip().scheduler().now()) return take(segment);
  deferred_.push_back(unit_.chip().scheduler().at(burst.start, [this, segment] {
    deferred_.pop_front();
    take(segment);
  }));
}

void SerialReceiver::take(const RxdSegment& segment) {
  const sim::Time now = unit_.chip().scheduler().now();
  const bool cuts = current_.active && now < current_.cut;
  cut_current(now);
  const RxdSegment before = input_;
  input_ = segment;
  if (!unit_.running()) return;
  unit_.monitor().input_changed(before, input_);
  if (segment.is_burst) receive(segment);
  // Once, after both: a telegram cut by the next one keeps RECACTN low across the seam.
  if (cuts || segment.is_burst) schedule_recact();
  unit_.repeater().input(segment);
}

void SerialReceiver::cut_current(sim::Time at) {
  if (!current_.active) return;
  current_.active = false;
  if (at >= current_.cut) return;  // ended whole
  const auto cut_bit = static_cast<std::size_t>((at - current_.start) / current_.period);
  const BurstDecode& old = *current_.decode;
  // Frames whose closing flag came before the cut stand; the rest are decoded again.
  std::size_t first = 0;
  while (first < old.frames.size() && old.frames[first].end_bit <= cut_bit) ++first;
  sim::Scheduler& s = unit_.chip().scheduler();
  std::vector<std::size_t> started;  // start bits of frames whose start event already ran
  for (std::size_t i = first; i < current_.events.size(); ++i) {
    const FrameEvents& e = current_.events[i];
    if (e.address != kNone && !s.pending(e.address_event)) {
      started.push_back(old.frames[i].start_bit);
    }
    cancel_report(e.address, e.address_event);
    cancel_report(e.detected, e.detected_event);
  }
  current_.decode = decode_burst_prefix(current_.bits, cut_bit);
  current_.cut = at;
  current_.events.resize(first);
  current_.events.resize(current_.decode->frames.size());
  for (std::size_t i = first; i < current_.events.size(); ++i) {
    const std::size_t start_bit = current_.decode->frames[i].start_bit;
    current_.events[i].address_done =
        std::find(started.begin(), started.end(), start_bit) != started.end();
  }
  schedule_frames(first);
}

// Reports of a finished burst can no longer be cut: they just wait for their time.
void SerialReceiver::retire_current() { current_.events.clear(); }

void SerialReceiver::receive(const RxdSegment& burst) {
  if (burst.period != unit_.bit_period()) return;  // distorted: the monitor counts it
  retire_current();
  current_.active = true;
  current_.start = burst.since;
  current_.period = burst.period;
  current_.cut = burst.burst_end();
  current_.bits = burst.bits;
  current_.decode = decode_burst(burst.bits);
  current_.events.assign(current_.decode->frames.size(), FrameEvents{});
  schedule_frames(0);
}

sim::Time SerialReceiver::pipeline(sim::Time t) const {
  const Chip& chip = unit_.chip();
  const sim::Time half_bits = (11 * current_.period + 1) / 2;  // 5.5 bit times
  // Three MCLK edges after the first one at or after t + 5.5 bits.
  const MclkGrid& mclk = chip.mclk();
  return mclk.time_of(mclk.first_at_or_after(t + half_bits) + 3);
}

void SerialReceiver::schedule_frames(std::size_t first) {
  sim::Scheduler& s = unit_.chip().scheduler();
  const std::shared_ptr<const BurstDecode> decode = current_.decode;
  for (std::size_t i = first; i < decode->frames.size(); ++i) {
    const wire::DecodedFrame& f = decode->frames[i];
    FrameEvents& e = current_.events[i];
    const sim::Time start = current_.start + static_cast<sim::Time>(f.start_bit) * current_.period;
    const sim::Time end = std::min(
        current_.start + static_cast<sim::Time>(f.end_bit) * current_.period, current_.cut);
    const std::size_t address_end = decode->address_end[i];
    const sim::Time address_in =
        current_.start + static_cast<sim::Time>(address_end) * current_.period;
    if (on_start_ && !e.address_done && address_end <= f.end_bit && address_in <= current_.cut) {
      e.address = schedule_report(std::max(pipeline(address_in), s.now()),
                                  Report{decode, i, start, end, 0, false, {}});
      e.address_event = reports_[e.address].event;
    }
    if (on_telegram_) {
      const sim::Time detected = pipeline(end);
      e.detected = schedule_report(detected, Report{decode, i, start, end, detected, true, {}});
      e.detected_event = reports_[e.detected].event;
    }
  }
}

void SerialReceiver::schedule_recact() {
  sim::Scheduler& s = unit_.chip().scheduler();
  s.cancel(recact_event_);
  if (!current_.decode || current_.decode->frames.empty()) return set_recact(false);
  const std::vector<wire::DecodedFrame>& frames = current_.decode->frames;
  const sim::Time begin =
      current_.start + static_cast<sim::Time>(frames.front().start_bit) * current_.period;
  const sim::Time end =
      std::min(current_.start + static_cast<sim::Time>(frames.back().end_bit) * current_.period,
               current_.cut);
  const sim::Time now = s.now();
  if (now >= end) return set_recact(false);
  if (now >= begin) {
    set_recact(true);
    recact_event_ = s.at(end, [this] { set_recact(false); });
  } else {
    set_recact(false);
    recact_event_ = s.at(begin, [this] { schedule_recact(); });
  }
}

void SerialReceiver::set_recact(bool active) {
  if (active == recact_) return;
  recact_ = active;
  unit_.chip().set_output(Pin::RECACTN, !active);
  unit_.fields().recact.set(unit_.chip().regs(), active);
}

}  // namespace sercon::chip

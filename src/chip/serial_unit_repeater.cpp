#include "sercon/chip/serial_unit_repeater.hpp"

#include <algorithm>

#include "sercon/chip/chip.hpp"
#include "sercon/chip/serial_unit.hpp"
#include "sercon/chip/serial_unit_fields.hpp"
#include "sercon/chip/serial_unit_outputs.hpp"
#include "sercon/chip/serial_unit_pass_through.hpp"
#include "sercon/chip/serial_unit_receiver.hpp"

namespace sercon::chip {

SerialRepeater::SerialRepeater(SerialUnit& unit)
    : unit_(unit),
      scheduler_(unit.chip().scheduler()),
      sclk_period_(sim::period_of_hz(unit.chip().config().sclk_hz)),
      by_sclk_(static_cast<std::uint64_t>(sclk_period_)) {}

void SerialRepeater::reset() {
  absorb_passed();
  repon_ = false;
  unit_.receiver().refresh_hop_period();
  background_.clear();
  own_.drop_all();
  own_end_ = 0;
  unit_.outputs().line_condition(scheduler_.now(), LineCondition::Dark, 0);
}

void SerialRepeater::release() {
  absorb_passed();
  repon_ = unit_.fields().repon.on(unit_.chip().regs());
  unit_.receiver().refresh_hop_period();
  const sim::Time now = scheduler_.now();
  background_.clear();
  if (repon_) {
    take_up_received();
  } else {
    background_.push_back(RxdSegment::of(now, LineCondition::Idle, unit_.bit_period()));
  }
  emit_from(now);
}

// Switched on: the line takes up what RxD carries now at once (a telegram half-way through
// is not picked up: its rest would decode to nothing), and what RxD is told of for later
// leaves after the repeater delay.
void SerialRepeater::take_up_received() {
  const sim::Time now = scheduler_.now();
  const std::vector<RxdSegment> received = unit_.receiver().input_from_now();
  const RxdSegment& current = received.front();
  background_.clear();
  background_.push_back(RxdSegment::of(now, current.condition_at_join(), current.period));
  for (std::size_t i = 1; i < received.size(); ++i) {
    RxdSegment s = received[i];
    s.since = std::max(forward_time(s.since), now);
    drop_announced_from(background_, s.since);
    background_.push_back(std::move(s));
  }
}

void SerialRepeater::absorb_forwarded_now(sim::Time next) {
  const sim::Time now = scheduler_.now();
  const sim::Time delay = unit_.outputs().follower_delay();
  // The usual (an own telegram absorbs the burst after them): what follows has reached TxD's
  // listener, so every one of them is over (they all leave before it) and none is booked.
  if (next + delay <= now) return forwarded_.drop_all();
  // A booking out of order (a missed trigger) throws; the bursts are let go then, so the
  // node does not throw again at every later absorb.
  struct LetGo {
    sim::CircularQueue<Forwarded>& forwarded;
    ~LetGo() { forwarded.drop_all(); }
  } let_go{forwarded_};
  while (forwarded_.size() > 1 && forwarded_[1].leaves + delay <= now) forwarded_.drop_front();
  // Mostly (an own telegram where no lazy burst waits, the first slave's) the last one has
  // reached TxD's listener: the line and TxD's are set to it alone (settle).
  if (forwarded_.size() == 1 && settles(forwarded_.front().leaves, scheduler_.now())) {
    Forwarded& f = forwarded_.front();
    return settle(f.leaves, f.reaching.bit_period, std::move(f.reaching.bits));  // drops forwarded_
  }
  for (std::size_t i = 0; i < forwarded_.size(); ++i) {
    const Forwarded& f = forwarded_[i];
    book(f.leaves, f.reaching.bit_period, f.reaching.bits);
  }
}

void SerialRepeater::refresh() {
  absorb_passed();
  const bool on = unit_.fields().repon.on(unit_.chip().regs());
  const sim::Time now = scheduler_.now();
  if (on != repon_) {
    repon_ = on;
    unit_.receiver().refresh_hop_period();
    if (on) {
      take_up_received();
    } else {
      background_.clear();
      background_.push_back(RxdSegment::of(now, LineCondition::Idle, unit_.bit_period()));
    }
  } else if (!repon_) {
    // The own idle fill at a new bit rate (from the end of an own telegram under way).
    drop_announced_from(background_, now);
    background_.push_back(RxdSegment::of(now, LineCondition::Idle, unit_.bit_period()));
  } else {
    return;  // REPON = 1: the received signal goes on as it was announced
  }
  prune();
  emit_from(now);
}

// Background segment `index` from `at` on: as it is when it begins there, else joined
// half-way (a telegram counts as the idle fill after it).
void SerialRepeater::emit_background(sim::Time at, std::size_t index, bool joined) {
  const RxdSegment& s = background_[index];
  TxdOutputs& out = unit_.outputs();
  if (!joined && s.since == at && s.is_burst) return out.line_burst(s.burst());
  if (!joined && s.since == at) return out.line_condition(at, s.condition, s.period);
  out.line_condition(at, s.condition_at_join(), s.period);
}

void SerialRepeater::emit_from(sim::Time t) {
  if (background_.empty()) return;
  TxdOutputs& out = unit_.outputs();
  std::size_t k = 0;  // next own telegram
  while (k < own_.size() && own_[k].end() <= t) ++k;
  std::size_t j = 0;  // background segment in force at `pos`
  const auto seek = [this, &j](sim::Time at) {
    while (j + 1 < background_.size() && background_[j + 1].since <= at) ++j;
  };
  sim::Time pos = t;
  bool inside_own = k < own_.size() && own_[k].start <= t;
  if (!inside_own) {
    seek(pos);
    emit_background(pos, j, background_[j].since != pos);
  }
  for (;;) {
    if (inside_own) {
      if (own_[k].start == pos) {
        const LineBurst burst = own_[k];  // a copy: the call may add to own_
        out.line_burst(burst);
      }
      pos = own_[k].end();
      ++k;
      inside_own = false;
      if (k < own_.size() && own_[k].start == pos) {  // back to back
        inside_own = true;
        continue;
      }
      seek(pos);
      emit_background(pos, j, background_[j].since != pos);
    }
    const sim::Time next_own = k < own_.size() ? own_[k].start : LineBurst{}.start;
    const bool more_own = k < own_.size();
    // Background segments that begin before the next own telegram leave as they are.
    while (j + 1 < background_.size() && (!more_own || background_[j + 1].since < next_own)) {
      ++j;
      emit_background(background_[j].since, j, false);
    }
    if (!more_own) return;
    pos = next_own;
    inside_own = true;
  }
}

}  // namespace sercon::chip

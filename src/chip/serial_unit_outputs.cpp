#include "sercon/chip/serial_unit_outputs.hpp"

#include <stdexcept>
#include <string>
#include <vector>

#include "sercon/chip/chip.hpp"
#include "sercon/chip/serial_unit.hpp"
#include "sercon/chip/serial_unit_fields.hpp"
#include "sercon/chip/serial_unit_pass_through.hpp"
#include "sercon/chip/serial_unit_receiver.hpp"

namespace sercon::chip {
namespace {

std::size_t index_of_pin(unsigned pin) {
  if (pin < 1 || pin > SerialUnit::kTxdCount) {
    throw std::out_of_range("TxD" + std::to_string(pin) + ": the chip has TxD1..TxD6");
  }
  return pin - 1;
}

}  // namespace

TxdOutputs::TxdOutputs(SerialUnit& unit) : unit_(unit), scheduler_(unit.chip().scheduler()) {
  line_.push_back(RxdSegment::of(0, LineCondition::Dark, 0));
}

TxdOutputs::~TxdOutputs() { scheduler_.cancel(pins_event_); }

void TxdOutputs::pass_on(LineListener& listener, const RxdSegment& s) {
  if (s.is_burst) return listener.line_burst(s.burst());
  listener.line_condition(s.since, s.condition, s.period);
}

// A listener that joins (or whose pin goes back to the line) gets the line now, then what
// is announced for later. Taken out first: in a ring where every node repeats, what the
// listener is told comes back round to this line and changes it during the telling.
void TxdOutputs::tell_line(LineListener& listener) const {
  sim::Time period = 0;
  const LineCondition c = line_condition_now(&period);
  const sim::Time now = scheduler_.now();
  std::vector<RxdSegment> later;
  for (std::size_t i = 0; i < line_.size(); ++i) {
    if (line_[i].since > now) later.push_back(line_[i]);
  }
  listener.line_condition(now, c, period);
  for (const RxdSegment& s : later) pass_on(listener, s);
}

void TxdOutputs::connect(unsigned pin, LineListener& listener) {
  book_all();  // the follower may change
  Output& out = outputs_[index_of_pin(pin)];
  LineListener* const replaced = out.listener;
  out.listener = &listener;
  find_lone_follower();
  if (replaced != &listener) tell_left_dark(replaced);
  const View& v = out.view;
  if (v.mode == Mode::Line) {
    tell_line(listener);
  } else {
    listener.line_condition(scheduler_.now(), v.condition, v.period);
  }
}

void TxdOutputs::disconnect(unsigned pin) {
  book_all();  // the follower may change
  Output& out = outputs_[index_of_pin(pin)];
  LineListener* const left = out.listener;
  out.listener = nullptr;
  find_lone_follower();
  tell_left_dark(left);
}

// A listener taken off a pin is no longer lit by this chip: Dark from now (unless another
// pin still drives it). Called after the pin is switched: what it is told may come back
// round to this line.
void TxdOutputs::tell_left_dark(LineListener* left) {
  if (left == nullptr) return;
  for (const Output& o : outputs_) {
    if (o.listener == left) return;
  }
  left->line_condition(scheduler_.now(), LineCondition::Dark, 0);
}

void TxdOutputs::find_lone_follower() {
  lone_follower_ = nullptr;
  for (const Output& o : outputs_) {
    if (o.view.mode != Mode::Line || o.listener == nullptr) continue;
    if (lone_follower_ != nullptr) {  // two listeners follow the line
      lone_follower_ = nullptr;
      break;
    }
    lone_follower_ = o.listener;
  }
  lone_link_ = lone_follower_ != nullptr ? lone_follower_->plain_link() : nullptr;
  if (link_mirror_ != nullptr) *link_mirror_ = lone_link_;
}

const RxdSegment& TxdOutputs::line_now() const {
  const sim::Time now = scheduler_.now();
  std::size_t i = line_.size() - 1;
  while (i > 0 && line_[i].since > now) --i;
  return line_[i];
}

LineCondition TxdOutputs::line_condition_now(sim::Time* period) const {
  unit_.repeater().absorb_passed();  // the own telegram left out of the line first
  const RxdSegment& s = line_now();
  *period = s.period;
  return s.is_burst ? LineCondition::Idle : s.condition;
}

void TxdOutputs::change_condition(sim::Time at, LineCondition condition, sim::Time period) {
  book_own();
  prune();
  const bool dropped = drop_from(at);
  if (unbooked_ > 0) book_unbooked();  // booked before what the follower is told now
  line_.push_back(RxdSegment::of(at, condition, period));
  if (lone_follower_ != nullptr) {
    lone_follower_->line_condition(at, condition, period);
  } else {
    for (Output& out : outputs_) {
      if (out.view.mode == Mode::Line && out.listener) {
        out.listener->line_condition(at, condition, period);
      }
    }
  }
  if (dropped || darkness_changes_at_back()) plan_pins();
}

void TxdOutputs::book_all() {
  // The bursts passed on into the line, unbooked (the own telegram left out of it first).
  unit_.repeater().absorb_passed();
  if (unbooked_ > 0) book_unbooked();
}

// Where line_burst() would have put it, with nothing to prune or drop before it (own_burst):
// nothing has changed the line since (every way in books it first).
void TxdOutputs::book_own_now() {
  const LineBurst& own = *own_unbooked_;
  own_unbooked_ = nullptr;
  append_burst(line_, own, own.start);
  ++unbooked_;
}

void TxdOutputs::book_unbooked() {
  const std::size_t first = line_.size() - unbooked_;
  unbooked_ = 0;
  for (std::size_t i = first; i < line_.size(); ++i) lone_follower_->book_passed(line_[i].burst());
}

bool TxdOutputs::follower_takes_copy(sim::Time leaves, LineBurst& into, LineListener*& next) {
  const LineBurst leaving{leaves, into.bit_period, into.bits};
  const LineBurst* out = nullptr;
  if (!lone_follower_->pass_through(leaving, next, out, *this)) return false;
  // The caller books its own bits later (absorb): a listener must pass them on unchanged.
  if (out->bits != into.bits || out->bit_period != into.bit_period) {
    throw std::logic_error("TxD: a listener's pass_through changed the burst it passed on");
  }
  into.start = out->start;
  return true;
}

// Not one listener following the line: each that does is told.
void TxdOutputs::tell_followers(const LineBurst& burst) {
  for (Output& out : outputs_) {
    if (out.view.mode == Mode::Line && out.listener) out.listener->line_burst(burst);
  }
}

bool TxdOutputs::dark_now() const { return is_dark(line_now()); }

// The TxD pins show whether there is a signal (light level) or none (dark level): they
// change only where the line goes dark or lights up, rarely, so an event there is cheap.
void TxdOutputs::plan_pins() {
  sim::Scheduler& s = scheduler_;
  s.cancel(pins_event_);
  pins_event_ = {};
  set_pins_following_line();
  for (std::size_t i = 1; i < line_.size(); ++i) {
    if (is_dark(line_[i]) == is_dark(line_[i - 1])) continue;
    pins_event_ = s.at(line_[i].since, [this] {
      pins_event_ = {};
      unit_.repeater().absorb_passed();
      prune();
      plan_pins();
    });
    return;
  }
}

TxdOutputs::View TxdOutputs::view_of(unsigned pin) const {
  Chip& chip = unit_.chip();
  const RegisterFile& regs = chip.regs();
  const SerialFields& f = unit_.fields();
  View v;
  if (!unit_.running()) return v;  // reset: high impedance (TXOE = 0)
  const auto bit = [](std::uint16_t field, unsigned n) {
    return ((unsigned{field} >> n) & 1u) != 0;
  };
  if (pin >= 2 && bit(f.portsel.get(regs), pin - 2)) {
    // Port mode (datasheet Table 1: high impedance is a feature of the data function).
    v.mode = Mode::Port;
    const bool high = bit(f.portval.get(regs), pin - 2);
    v.condition = high != f.poltxd.on(regs) ? LineCondition::Light : LineCondition::Dark;
    return v;
  }
  if (!bit(f.txoe.get(regs), pin - 1)) return v;
  if (!f.txlight.on(regs)) {
    v.mode = Mode::Dark;
    return v;
  }
  switch (chip.test_mode()) {
    case TestMode::ContinuousLight:
      v.mode = Mode::Light;
      v.condition = LineCondition::Light;
      return v;
    case TestMode::ZeroBitStream:
      v.mode = Mode::ZeroBits;
      v.condition = LineCondition::ZeroBits;
      v.period = unit_.bit_period();
      return v;
    case TestMode::None:
      break;
  }
  v.mode = Mode::Line;
  return v;
}

sim::Level TxdOutputs::pin_level(const View& v) const {
  const RegisterFile& regs = unit_.chip().regs();
  const SerialFields& f = unit_.fields();
  if (v.mode == Mode::HighZ) return sim::Level::HighZ;
  if (v.mode == Mode::Port) {
    return sim::level_of((v.condition == LineCondition::Light) != f.poltxd.on(regs));
  }
  // A line with edges is not drawn bit by bit: the pin shows the light level while there
  // is a signal, the dark level while there is none.
  const bool dark = v.mode == Mode::Dark || (v.mode == Mode::Line && dark_now());
  return sim::level_of(!dark != f.poltxd.on(regs));
}

void TxdOutputs::show(unsigned pin, const View& v) {
  Output& out = outputs_[pin - 1];
  unit_.chip().set_output(txd_pin(pin), pin_level(v));
  if (out.view == v) return;
  out.view = v;
  find_lone_follower();
  if (!out.listener) return;
  if (v.mode == Mode::Line) {
    prune();
    tell_line(*out.listener);
  } else {
    out.listener->line_condition(scheduler_.now(), v.condition, v.period);
  }
}

void TxdOutputs::refresh() {
  book_all();  // the follower may change
  for (unsigned pin = 1; pin <= SerialUnit::kTxdCount; ++pin) show(pin, view_of(pin));
}

void TxdOutputs::set_pins_following_line() {
  for (unsigned pin = 1; pin <= SerialUnit::kTxdCount; ++pin) {
    const View& v = outputs_[pin - 1].view;
    if (v.mode == Mode::Line) unit_.chip().set_output(txd_pin(pin), pin_level(v));
  }
}

}  // namespace sercon::chip

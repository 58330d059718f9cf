#include "sercon/ring/fibre.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace sercon::ring {

using chip::LineBurst;
using chip::LineCondition;
using chip::SharedBits;

namespace {

sim::Time delay_of(double length_m, sim::Time ps_per_metre) {
  if (!std::isfinite(length_m) || length_m < 0.0) {
    throw std::invalid_argument("Fibre: length " + std::to_string(length_m) +
                                " m is not a finite length >= 0");
  }
  if (ps_per_metre < 0) {
    throw std::invalid_argument("Fibre: " + std::to_string(ps_per_metre) +
                                " ps per metre is negative");
  }
  const double ps = std::round(length_m * static_cast<double>(ps_per_metre));
  if (ps > 1e15) throw std::invalid_argument("Fibre: a delay above 1000 s is not a fibre");
  return static_cast<sim::Time>(ps);
}

bool toggles(LineCondition c) { return c == LineCondition::Idle || c == LineCondition::ZeroBits; }

}  // namespace

Fibre::Fibre(sim::Scheduler& scheduler, double length_m, sim::Time ps_per_metre)
    : scheduler_(scheduler),
      length_m_(length_m),
      delay_(delay_of(length_m, ps_per_metre)),
      link_(scheduler, delay_) {}

Fibre::~Fibre() {
  for (const auto id : switches_) scheduler_.cancel(id);
}

void Fibre::connect(chip::LineListener& output) {
  book_passed();
  chip::LineListener* const old = output_;
  output_ = &output;
  update_plain();
  // The receiver it leaves has no signal any more, as after a break. Switched first: what
  // the old receiver is told may come back round into this fibre.
  if (old != nullptr && old != &output) {
    old->line_condition(scheduler_.now(), LineCondition::Dark, 0);
  }
  tell_far_end();
}

void Fibre::disconnect() {
  chip::LineListener* const old = output_;
  output_ = nullptr;
  update_plain();
  if (old != nullptr) old->line_condition(scheduler_.now(), LineCondition::Dark, 0);
}

void Fibre::Input::line_condition(sim::Time at, LineCondition condition, sim::Time period) {
  if (toggles(condition) ? period <= 0 : period < 0) {
    throw std::invalid_argument("Fibre input: " + std::string(chip::to_string(condition)) +
                                " with bit period " + std::to_string(period) + " ps");
  }
  Change c;
  c.condition = condition;
  c.burst.start = at;
  c.burst.bit_period = toggles(condition) ? period : 0;
  fibre_.take(std::move(c));
}

void Fibre::Input::line_burst(const LineBurst& burst) {
  if (!burst.bits || burst.bit_period <= 0) {
    throw std::invalid_argument("Fibre input: a burst needs bits and a bit period > 0");
  }
  Fibre& f = fibre_;
  if (burst.start < f.scheduler_.now()) [[unlikely]]
    f.check_not_past(burst.start);
  f.book_passed();
  // Read first: `burst` may live in this history (a TxD looped back to its own RxD).
  const sim::Time start = burst.start + f.delay_;
  const sim::Time period = burst.bit_period;
  SharedBits bits = f.errors_.enabled() ? f.errors_.apply(burst.bits) : burst.bits;
  Change& c = f.record_at(start);
  c.is_burst = true;
  c.burst.start = start;
  c.burst.bit_period = period;
  c.burst.bits = std::move(bits);
  if (!f.broken_) f.pass_on(c);
}

void Fibre::check_not_past(sim::Time at) const {
  const sim::Time now = scheduler_.now();
  if (at < now) {
    throw std::invalid_argument("Fibre input: a change at " + std::to_string(at) +
                                " ps is before now (" + std::to_string(now) + " ps)");
  }
}

void Fibre::take(Change change) {
  check_not_past(change.burst.start);
  book_passed();
  change.burst.start += delay_;
  if (change.is_burst && errors_.enabled()) change.burst.bits = errors_.apply(change.burst.bits);
  record_at(change.burst.start) = std::move(change);
  if (!broken_) pass_on(history_.back());
}

// The later word wins (line.hpp); what is no longer in force at the far end is forgotten.
// Inline: every burst booked here goes through it (those a sender passed through unbooked
// when the history is read, book_passed).
inline Fibre::Change& Fibre::record_at(sim::Time start) {
  if (!history_.empty() && history_.back().burst.start >= start) drop_from(start);
  const sim::Time now = scheduler_.now();
  while (history_.size() > 1 && history_[1].burst.start <= now) history_.pop_front();
  return history_.emplace_back();
}

// Rare (a later word overtaking one announced before): kept out of record_at's code.
void Fibre::drop_from(sim::Time start) {
  while (!history_.empty() && history_.back().burst.start >= start) history_.pop_back();
}

// A lazy hop (line.hpp): whole and without bit errors, the fibre passes a burst on as it
// is, so the sender may deliver it to the far end itself. The sender keeps it and books it
// here when asked (book_passed): a history entry per hop cost as much as the rest of it.
// Bursts from another sender still waiting to be booked: the full path, which books them.
// A chip's TxD asks the link inline (PlainLink); this is for other senders.
bool Fibre::Input::pass_through(const LineBurst& burst, chip::LineListener*& next,
                                const LineBurst*& out, chip::PassedBursts& sender) {
  return fibre_.link_.pass(burst, sender, next, out);
}

void Fibre::Input::book_passed(const LineBurst& burst) {
  Fibre& f = fibre_;
  const sim::Time start = burst.start + f.delay_;
  const sim::Time period = burst.bit_period;
  SharedBits bits = burst.bits;
  Change& c = f.record_at(start);
  c.is_burst = true;
  c.burst.start = start;
  c.burst.bit_period = period;
  c.burst.bits = std::move(bits);
  f.link_.booked(start);
}

void Fibre::pass_on(const Change& c) {
  if (!output_) return;
  if (c.is_burst) return output_->line_burst(c.burst);
  output_->line_condition(c.burst.start, c.condition, c.burst.bit_period);
}

void Fibre::tell_far_end() {
  book_passed();
  if (!output_) return;
  const sim::Time now = scheduler_.now();
  if (broken_) return output_->line_condition(now, LineCondition::Dark, 0);
  // In force now: the last change that has reached the far end. A telegram already under
  // way is a fragment without its opening flag: the idle fill after it.
  std::size_t next = 0;
  while (next < history_.size() && history_[next].burst.start <= now) ++next;
  if (next == 0) {
    output_->line_condition(now, LineCondition::Dark, 0);
  } else {
    const Change& c = history_[next - 1];
    if (c.is_burst && c.burst.start == now) {
      output_->line_burst(c.burst);
    } else {
      output_->line_condition(now, c.is_burst ? LineCondition::Idle : c.condition,
                              c.burst.bit_period);
    }
  }
  // Still on their way. Taken out first: in a loop (a node's TxD back to its own RxD) what is
  // passed on comes back into this history while it is walked.
  std::vector<Change> on_their_way;
  for (std::size_t i = next; i < history_.size(); ++i) on_their_way.push_back(history_[i]);
  for (const Change& c : on_their_way) pass_on(c);
}

void Fibre::break_now() {
  if (broken_) return;
  broken_ = true;
  update_plain();
  tell_far_end();
}

void Fibre::restore() {
  if (!broken_) return;
  broken_ = false;
  update_plain();
  tell_far_end();
}

void Fibre::break_at(sim::Time t) {
  if (t < scheduler_.now()) throw std::invalid_argument("Fibre::break_at: time in the past");
  std::erase_if(switches_, [this](sim::Scheduler::EventId id) { return !scheduler_.pending(id); });
  switches_.push_back(scheduler_.at(t, [this] { break_now(); }));
}

void Fibre::restore_at(sim::Time t) {
  if (t < scheduler_.now()) throw std::invalid_argument("Fibre::restore_at: time in the past");
  std::erase_if(switches_, [this](sim::Scheduler::EventId id) { return !scheduler_.pending(id); });
  switches_.push_back(scheduler_.at(t, [this] { restore(); }));
}

void Fibre::set_bit_error_rate(double p, std::uint64_t seed) {
  errors_.configure(p, seed);
  update_plain();
}

}  // namespace sercon::ring

#include "sercon/ring/fibre.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace sercon::ring {

using chip::LineBurst;
using chip::LineCondition;

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
    : scheduler_(scheduler), length_m_(length_m), delay_(delay_of(length_m, ps_per_metre)) {}

Fibre::~Fibre() {
  for (const Delivery& d : pending_) scheduler_.cancel(d.event);
  for (const auto id : switches_) scheduler_.cancel(id);
}

void Fibre::connect(chip::LineListener& output) {
  output_ = &output;
  tell_far_end();
}

void Fibre::check_order(sim::Time at) {
  if (at < scheduler_.now()) {
    throw std::invalid_argument("Fibre input: a change at " + std::to_string(at) +
                                " ps is before now (" + std::to_string(scheduler_.now()) + " ps)");
  }
  if (at < last_input_) {
    throw std::invalid_argument("Fibre input: a change at " + std::to_string(at) +
                                " ps comes after one at " + std::to_string(last_input_) + " ps");
  }
  last_input_ = at;
}

// Deliveries wait in pending_ (time order); each event is a plain function + `this`.
void Fibre::schedule(Delivery delivery) {
  const sim::Time at = delivery.burst.start;
  pending_.push_back(std::move(delivery));
  pending_.back().event = scheduler_.at(
      at, [](void* self) { static_cast<Fibre*>(self)->deliver(); }, this);
}

void Fibre::deliver() {
  const Delivery d = std::move(pending_.front());
  pending_.pop_front();
  if (d.is_burst) return deliver_burst(d.burst);
  deliver_condition(d.burst.start, d.condition, d.burst.bit_period);
}

void Fibre::Input::line_condition(sim::Time at, LineCondition condition, sim::Time period) {
  if (toggles(condition) ? period <= 0 : period < 0) {
    throw std::invalid_argument("Fibre input: " + std::string(chip::to_string(condition)) +
                                " with bit period " + std::to_string(period) + " ps");
  }
  fibre_.check_order(at);
  Delivery d;
  d.condition = condition;
  d.burst.start = at + fibre_.delay_;
  d.burst.bit_period = toggles(condition) ? period : 0;
  fibre_.schedule(std::move(d));
}

void Fibre::Input::line_burst(const LineBurst& burst) {
  if (!burst.bits || burst.bit_period <= 0) {
    throw std::invalid_argument("Fibre input: a burst needs bits and a bit period > 0");
  }
  fibre_.check_order(burst.start);
  Delivery d;
  d.is_burst = true;
  d.burst = burst;
  d.burst.start += fibre_.delay_;
  if (fibre_.errors_.enabled()) d.burst.bits = fibre_.errors_.apply(burst.bits);
  fibre_.schedule(std::move(d));
}

void Fibre::deliver_condition(sim::Time at, LineCondition condition, sim::Time period) {
  far_ = FarEnd{false, condition, period, at};
  if (!broken_ && output_) output_->line_condition(at, condition, period);
}

void Fibre::deliver_burst(const LineBurst& burst) {
  far_ = FarEnd{true, LineCondition::Idle, burst.bit_period, burst.end()};
  if (!broken_ && output_) output_->line_burst(burst);
}

void Fibre::tell_far_end() {
  if (!output_) return;
  const sim::Time now = scheduler_.now();
  if (broken_) return output_->line_condition(now, LineCondition::Dark, 0);
  // A telegram already under way is a fragment without its opening flag: idle fill.
  output_->line_condition(now, far_.condition, far_.period);
}

void Fibre::break_now() {
  if (broken_) return;
  broken_ = true;
  tell_far_end();
}

void Fibre::restore() {
  if (!broken_) return;
  broken_ = false;
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

void Fibre::set_bit_error_rate(double p, std::uint64_t seed) { errors_.configure(p, seed); }

}  // namespace sercon::ring

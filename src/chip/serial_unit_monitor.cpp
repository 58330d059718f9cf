#include "sercon/chip/serial_unit_monitor.hpp"

#include <algorithm>

#include "sercon/chip/chip.hpp"
#include "sercon/chip/interrupts.hpp"
#include "sercon/chip/serial_unit.hpp"
#include "sercon/chip/serial_unit_fields.hpp"
#include "sercon/chip/serial_unit_receiver.hpp"

namespace sercon::chip {

void LineMonitor::cancel() {
  unit_.chip().scheduler().cancel(rdist_event_);
  unit_.chip().scheduler().cancel(fibbr_event_);
}

void LineMonitor::reset() {
  cancel();
  distorted_ = skipped_ = 0;
  rdist_ = fibbr_ = false;  // the register reset cleared the bits, the chip's reset L_ERRN
}

void LineMonitor::release() {
  segment_ = unit_.receiver().input();
  // The monitor's counters start at release: darkness before it does not count.
  const sim::Time now = unit_.chip().scheduler().now();
  if (!segment_.has_edges()) segment_.since = now;
  skipped_ = edges_before(segment_, now);
  period_ = unit_.bit_period();
  evaluate();
  refresh_line_error();
}

void LineMonitor::input_changed(const RxdSegment& before, const RxdSegment& after) {
  const sim::Time now = unit_.chip().scheduler().now();
  cancel();
  if (before.has_edges() && before.period != period_) {
    std::uint64_t edges = edges_before(before, now);
    if (before.since == segment_.since) edges -= std::min(edges, skipped_);
    distorted_ += edges;
  }
  segment_ = after;
  skipped_ = 0;
  evaluate();
}

void LineMonitor::refresh_limits() {
  const sim::Time now = unit_.chip().scheduler().now();
  cancel();
  const sim::Time period = unit_.bit_period();
  // Between bad signals the monitor is not told of changes (the receiver's plan_monitor):
  // take up what RxD carries now.
  if (const RxdSegment& in = unit_.receiver().input(); in.since > segment_.since) {
    segment_ = in;
    skipped_ = 0;
  }
  if (period != period_) {
    // A new rate: what RxD carries now is judged by it from now on, edge by edge where the
    // signal has them (a telegram's level changes, then its trailing fill's).
    const std::uint64_t before_now = edges_before(segment_, now);
    if (segment_.has_edges() && segment_.period != period_) {
      distorted_ += before_now - std::min(before_now, skipped_);
    }
    skipped_ = before_now;
    period_ = period;
  }
  evaluate();
}

void LineMonitor::evaluate() {
  const sim::Time period = period_;
  if (!unit_.running() || period == 0) return;
  sim::Scheduler& s = unit_.chip().scheduler();
  const RegisterFile& regs = unit_.chip().regs();
  const SerialFields& f = unit_.fields();
  const sim::Time now = s.now();
  if (!segment_.has_edges()) {
    if (fibbr_) return;
    const auto bits = std::max(f.fibbrtim.get(regs), kMinFibbrBits);
    const sim::Time due = segment_.since + static_cast<sim::Time>(bits) * period;
    if (due <= now) return set_fibbr(true);
    fibbr_event_ = s.at(due, [this] { set_fibbr(true); });
    return;
  }
  set_fibbr(false);
  if (segment_.period == period) {
    distorted_ = 0;
    return set_rdist(false);
  }
  const std::uint64_t limit = std::max<std::uint16_t>(f.rdistlim.get(regs), 1);
  if (distorted_ >= limit) return set_rdist(true);
  if (rdist_) return;
  const sim::Time due = nth_edge_time(segment_, skipped_ + limit - distorted_);
  if (due <= now) return set_rdist(true);
  rdist_event_ = s.at(due, [this] { set_rdist(true); });
}

void LineMonitor::set_rdist(bool on) {
  if (on == rdist_) return;
  rdist_ = on;
  unit_.fields().rdist.set(unit_.chip().regs(), on);
  if (auto* irq = unit_.chip().unit<Interrupts>()) irq->set_level(Irq::Rdist, on);
  refresh_line_error();
}

void LineMonitor::set_fibbr(bool on) {
  if (on == fibbr_) return;
  fibbr_ = on;
  unit_.fields().fibbr.set(unit_.chip().regs(), on);
  if (auto* irq = unit_.chip().unit<Interrupts>()) irq->set_level(Irq::Fibbr, on);
  refresh_line_error();
}

void LineMonitor::refresh_line_error() {
  if (!unit_.running()) return;
  const RegisterFile& regs = unit_.chip().regs();
  const SerialFields& f = unit_.fields();
  const bool error = (rdist_ && f.ledist.on(regs)) || (fibbr_ && f.lemiss.on(regs));
  unit_.chip().set_output(Pin::L_ERRN, !error);
}

}  // namespace sercon::chip

#include "sercon/chip/serial_unit_receiver.hpp"

#include <algorithm>
#include <cassert>
#include <stdexcept>
#include <string>

#include "sercon/chip/chip.hpp"
#include "sercon/chip/serial_unit_fields.hpp"
#include "sercon/chip/serial_unit_monitor.hpp"
#include "sercon/chip/serial_unit_pass_through.hpp"
#include "sercon/chip/serial_unit_receiver_inline.hpp"
#include "sercon/chip/serial_unit_repeater.hpp"
#include "sercon/sim/model_limit.hpp"
#include "sercon/sim/scoped_count.hpp"

namespace sercon::chip {

using receiver_detail::chain_depth;
using receiver_detail::kMaxChain;
using receiver_detail::kNever;

namespace {
// A receiver holds what is in force and what is announced for later: a handful of telegrams
// in a real ring (at most 39 in a ring of 254 slaves with 250 m fibres, 256 with 4 km ones;
// 605 in a test's loop that ends). A ring where every node repeats, the master too,
// re-announces what circles it each time an own telegram is inserted, and that can grow
// without end; past this many an error names it instead of a hang. The plans walk the
// timeline at each change announced, so the way there costs about the square of this
// (docs/serial-and-ring.md, "Depth guard").
constexpr std::size_t kMaxTimeline = 1024;
}  // namespace

SerialReceiver::SerialReceiver(SerialUnit& unit)
    : LineListener(this),
      unit_(unit),
      scheduler_(unit.chip().scheduler()),
      txd_(unit.outputs()),
      mclk_(unit.chip().mclk()),
      recactn_(unit.chip(), Pin::RECACTN, *this) {
  txd_.mirror_lone_link(&hop_link_);
  start_report_event_ = scheduler_.own(
      [](void* self) { static_cast<SerialReceiver*>(self)->fire_report<false>(); }, this);
  telegram_report_event_ = scheduler_.own(
      [](void* self) { static_cast<SerialReceiver*>(self)->fire_report<true>(); }, this);
  timeline_.emplace_back(RxdSegment{}, 0, 0);
  const FieldRef& recact = unit.fields().recact;
  unit.chip().regs().on_read(recact.address, [this, mask = recact.mask](std::uint16_t stored) {
    const bool on = recact_at(scheduler_.now());
    return static_cast<std::uint16_t>(on ? stored | mask : stored & ~mask);
  });
}

SerialReceiver::~SerialReceiver() {
  txd_.mirror_lone_link(nullptr);
  scheduler_.disown(start_report_event_);
  scheduler_.disown(telegram_report_event_);
  scheduler_.cancel(monitor_event_);
  for (const Deferred& d : deferred_) scheduler_.cancel(d.event);
}

void SerialReceiver::on_start(SerialUnit::TelegramStartHandler handler) {
  start_function_ = std::move(handler);
  on_start_ = {};
  if (start_function_) {
    on_start_ = {[](void* f, sim::Time start, std::uint8_t address) {
                   (*static_cast<SerialUnit::TelegramStartHandler*>(f))(start, address);
                 },
                 &start_function_};
  }
  handlers_changed();
}

void SerialReceiver::on_telegram(SerialUnit::TelegramHandler handler) {
  telegram_function_ = std::move(handler);
  on_telegram_ = {};
  if (telegram_function_) {
    on_telegram_ = {[](void* f, const ReceivedTelegram& telegram) {
                      (*static_cast<SerialUnit::TelegramHandler*>(f))(telegram);
                    },
                    &telegram_function_};
  }
  handlers_changed();
}

void SerialReceiver::on_start(void* context, SerialUnit::TelegramStartFn handler) {
  start_function_ = nullptr;
  on_start_ = {handler, context};
  handlers_changed();
}

void SerialReceiver::on_telegram(void* context, SerialUnit::TelegramFn handler) {
  telegram_function_ = nullptr;
  on_telegram_ = {handler, context};
  handlers_changed();
}

void SerialReceiver::handlers_changed() {
  refresh_hop_check();
  plan_reports();
}

void SerialReceiver::set_interest(const ReceiveInterest* interest) {
  interest_ = interest;
  wants_ = interest != nullptr ? interest->published() : nullptr;
  refresh_hop_check();
  plan_reports();
}

bool SerialReceiver::ask_start(sim::Time start, std::uint8_t address) const {
  return interest_ == nullptr || interest_->wants_start(start, address);
}

bool SerialReceiver::ask_telegram(sim::Time start, const wire::DecodedFrame& frame) const {
  return interest_ == nullptr || interest_->wants_telegram(start, frame);
}

// --- the timeline -------------------------------------------------------------------------

void SerialReceiver::line_condition(sim::Time at, LineCondition condition, sim::Time bit_period) {
  const bool toggles = condition == LineCondition::Idle || condition == LineCondition::ZeroBits;
  if (toggles ? bit_period <= 0 : bit_period < 0) {
    throw std::invalid_argument("RxD: " + std::string(to_string(condition)) + " with bit period " +
                                std::to_string(bit_period) + " ps");
  }
  absorb_lazy();
  announce(RxdSegment::of(at, condition, toggles ? bit_period : 0));
}

void SerialReceiver::refuse_past(sim::Time at, sim::Time now) {
  throw std::invalid_argument("RxD: a change at " + std::to_string(at) + " ps is before now (" +
                              std::to_string(now) + " ps)");
}

void SerialReceiver::refuse_more(sim::Time now) const {
  throw sim::ModelLimit(
      "RxD: " + std::to_string(timeline_.size()) + " changes announced ahead at " +
      std::to_string(now) +
      " ps: telegrams circle a ring where every node repeats (REPON on everywhere, the "
      "master too); switch one repeater off, as Ring::switch_on_lines does for the master");
}

// A burst's entry is built in place from the LineBurst (no RxdSegment made and moved in).
// The lazy-hop loop that calls this is sensitive to code layout: a version where its call
// was one argument to an out-of-line announce(const LineBurst&) ran 20 % slower with 254
// slaves (fewer instructions); time it at 254 slaves after any change here
// (docs/performance.md, fourteenth and sixteenth sessions).
bool SerialReceiver::announce(sim::Time at, const LineBurst* burst, RxdSegment* segment,
                              Handed* handed) {
  const sim::Time now = scheduler_.now();
  if (at < now) refuse_past(at, now);
  // Mostly a change after everything announced before: nothing to drop or cut.
  const Entry& last = timeline_.back();
  const bool changed =
      (last.segment.since >= at || (last.segment.is_burst && at < last.cut)) && supersede(at);
  prune();
  if (timeline_.size() >= kMaxTimeline) refuse_more(now);
  Entry& e = burst != nullptr ? timeline_.emplace_back(*burst, next_serial_++)
                              : append(std::move(*segment));
  if (!unit_.running()) return false;
  take(e, true);
  if (changed) {
    plan_reports();
  } else {
    consider(e);
  }
  // Between good signals (the usual case) the monitor has nothing to hear. A burst taken is
  // one at the receiver's rate.
  const bool quiet = holds_more_than(1) && good((timeline_.end() - 2)->segment) &&
                     (e.decode != nullptr || good(e.segment));
  if (changed || !quiet || at == now) plan_monitor();
  recactn_.replan();
  if (handed != nullptr) return pass_handing(e, *handed);
  pass_to_repeater(e);
  return false;
}

inline void SerialReceiver::pass_to_repeater(const Entry& e) {
  if (chain_depth >= kMaxChain) return defer_forward(e);
  const sim::ScopedCount link(chain_depth);
  unit_.repeater().input(e.segment);
}

// What announce(burst, handed) does with such a burst, without asking again what the hop
// try has found: it is after now (no past to refuse, the monitor not due now), the unit
// runs at its rate (taken), the chain is short enough, its one frame decoded, the
// processor's answers known. The repeater is on (a hop try's read), or off (a master's
// read from announce_or_read(), which asks the answers: Full).
bool SerialReceiver::read(const LineBurst& b, HopTry wanted, Handed& handed) {
  const sim::Time at = b.start;
  const Entry& last = timeline_.back();
  // Nothing superseded or cut: `last` stays, before the new entry (prune() keeps two).
  const bool quiet = last.segment.since < at && !(last.segment.is_burst && at < last.cut);
  const bool changed = !quiet && supersede(at);
  const bool after_good = quiet && good(last.segment);  // the monitor hears nothing
  prune();
  if (timeline_.size() >= kMaxTimeline) refuse_more(scheduler_.now());
  Entry& e = timeline_.emplace_back(b, next_serial_++);
  take_one(e, decode_burst(b.bits));
  if (changed) {
    plan_reports();
  } else if (report_armed_) {
    consider_more(e);
  } else {
    consider_one(e, wanted);
  }
  // A burst taken: the monitor hears nothing after a good signal. Mostly nothing is to tell
  // it, nor RECACTN (replan() would do nothing), so nothing outside the node has run since
  // the hop try: the repeater is on at this rate, the chain short enough (pass_handing()
  // need not ask), and the burst leaves when a hop's would (at a master, nothing leaves).
  if (!after_good || !recactn_.idle()) [[unlikely]]
    return read_told(e, changed, handed);
  if (unrepeated_reads_) return false;  // the repeater is off: nothing goes on (pass_handing())
  ++chain_depth;
  const auto due = static_cast<std::uint64_t>(at + hop_due_);
  const sim::Time leaves = static_cast<sim::Time>(hop_by_sclk_.divide(due)) * hop_sclk_;
  return unit_.repeater().hand_read(e.segment, leaves, handed);
}

// read()'s end when the monitor or RECACTN is to be told (they may call out of the node).
bool SerialReceiver::read_told(const Entry& e, bool changed, Handed& handed) {
  if (changed || !holds_more_than(1) || !good((timeline_.end() - 2)->segment)) plan_monitor();
  recactn_.replan();
  return pass_handing(e, handed);
}

inline bool SerialReceiver::pass_handing(const Entry& e, Handed& handed) {
  if (chain_depth >= kMaxChain) return defer_forward(e), false;
  ++chain_depth;  // as pass_to_repeater()'s count, for the next receiver
  return unit_.repeater().input_handing(e.segment, handed);
}

// Go on when the change reaches RxD: the chain starts again from the scheduler.
void SerialReceiver::defer_forward(const Entry& e) {
  const std::uint64_t serial = e.serial;
  std::erase_if(deferred_, [this](const Deferred& d) { return !scheduler_.pending(d.event); });
  deferred_.push_back(Deferred{
      serial, scheduler_.at(e.segment.since, [this, serial] { forward_deferred(serial); })});
}

// The entry and what was announced after it go again, in order (an entry announced after
// it went straight on, and must not be overtaken by this late one). An entry superseded
// meanwhile goes nowhere: what replaced it went on when it was announced (and may lie in
// the past by now, so it must not go again).
void SerialReceiver::forward_deferred(std::uint64_t serial) {
  if (!unit_.running()) return;
  absorb_lazy();
  std::vector<RxdSegment> segments;
  bool still_there = false;
  for (const Entry& e : timeline_) {
    still_there = still_there || e.serial == serial;
    if (e.serial >= serial) segments.push_back(e.segment);
  }
  if (!still_there) return;
  const sim::ScopedCount link(chain_depth);
  for (const RxdSegment& s : segments) unit_.repeater().input(s);
}

// The later word wins (line.hpp): what was announced for `at` or later is dropped, and a
// burst under way at `at` is cut there.
bool SerialReceiver::supersede(sim::Time at) {
  bool changed = false;
  while (!timeline_.empty() && timeline_.back().segment.since >= at) {
    timeline_.pop_back();
    changed = true;
  }
  if (!timeline_.empty() && timeline_.back().segment.is_burst && at < timeline_.back().cut) {
    cut(timeline_.back(), at);
    changed = true;
  }
  return changed;
}

void SerialReceiver::cut(Entry& e, sim::Time at) {
  if (!e.segment.is_burst || at >= e.cut) return;  // ended whole
  e.cut = at;
  if (!e.decode) return;
  const sim::Time period = e.segment.period;
  const auto cut_bit = static_cast<std::size_t>((at - e.segment.since) / period);
  const BurstDecode& old = *e.decode;
  // Frames whose closing flag came before the cut stand; the rest are decoded again, and a
  // frame whose address was already reported keeps that report.
  std::size_t first = 0;
  while (first < old.frames.size() && old.frames[first].end_bit <= cut_bit) ++first;
  std::vector<std::size_t> started;
  for (std::size_t i = first; i < old.frames.size(); ++i) {
    if (e.frames[i].start_done) started.push_back(old.frames[i].start_bit);
  }
  e.decode = &decode_burst_prefix(e.segment.bits, cut_bit);
  e.frames.resize(first);
  e.frames.resize(e.decode->frames.size());
  work_out(e, first);
  for (std::size_t i = first; i < e.frames.size(); ++i) {
    const std::size_t start_bit = e.decode->frames[i].start_bit;
    e.frames[i].start_done = std::find(started.begin(), started.end(), start_bit) != started.end();
  }
}

void SerialReceiver::work_out_reports(Entry& e, std::size_t i) const { reports_of(e, i); }

// Inline in consider_one(), which works them out for nearly every frame read.
inline void SerialReceiver::reports_of(Entry& e, std::size_t i) const {
  FrameState& st = e.frames[i];
  const sim::Time since = e.segment.since, period = e.segment.period;
  const std::size_t address_end = e.decode->address_end[i];
  const std::size_t end_bit = e.decode->frames[i].end_bit;
  const sim::Time address_in = since + static_cast<sim::Time>(address_end) * period;
  st.telegram_report = pipeline(st.end, period);
  if (address_end > end_bit || address_in > e.cut) {
    st.start_report = kNever;  // no whole address
  } else if (const sim::Time end = since + static_cast<sim::Time>(end_bit) * period;
             grid_.shifts && period == grid_.period && st.end == end && end <= grid_.limit) {
    // Not cut: the address came a whole number of bits before the end (grid_).
    st.start_report = st.telegram_report - (end - address_in);
  } else {
    st.start_report = pipeline(address_in, period);
  }
  st.reports_known = st.telegram_known = true;
}

std::size_t SerialReceiver::in_force(sim::Time t) const {
  std::size_t i = timeline_.size() - 1;
  while (i > 0 && timeline_[i].segment.since > t) --i;
  return i;
}

SerialReceiver::Entry* SerialReceiver::find_before_last(std::uint64_t serial) {
  for (std::size_t i = 0; i + 1 < timeline_.size(); ++i) {
    if (timeline_[i].serial == serial) return &timeline_[i];
  }
  return nullptr;
}

const RxdSegment& SerialReceiver::input() const {
  absorb_lazy_to_read();
  return timeline_[in_force(scheduler_.now())].segment;
}

std::vector<RxdSegment> SerialReceiver::input_from_now() const {
  absorb_lazy_to_read();
  std::vector<RxdSegment> out;
  for (std::size_t i = in_force(scheduler_.now()); i < timeline_.size(); ++i) {
    out.push_back(timeline_[i].segment);
  }
  return out;
}

void SerialReceiver::reset() {
  absorb_lazy();
  cancel_report();
  scheduler_.cancel(monitor_event_);
  monitor_event_ = {};
  for (const Deferred& d : deferred_) scheduler_.cancel(d.event);
  deferred_.clear();
  for (Entry& e : timeline_) {
    e.decode = nullptr;
    e.frames.clear();
  }
  unit_.chip().set_output(Pin::RECACTN, true);
  recactn_.replan();
}

// Out of reset: the segment in force was not received (no opening flag seen); what is
// announced for later is taken as if announced now.
void SerialReceiver::release() {
  absorb_lazy();
  const sim::Time now = scheduler_.now();
  const std::size_t current = in_force(now);
  monitor_seen_ = timeline_[current].serial;
  monitor_last_ = timeline_[current].segment;
  for (std::size_t i = current + 1; i < timeline_.size(); ++i) take(timeline_[i]);
  plan_reports();
  plan_monitor();
  recactn_.replan();
  for (std::size_t i = current + 1; i < timeline_.size(); ++i) pass_to_repeater(timeline_[i]);
}

void SerialReceiver::refresh_rate() {
  absorb_lazy();
  if (!unit_.running()) return;
  const sim::Time now = scheduler_.now();
  const std::size_t current = in_force(now);
  // The receiver is clocked at the new rate from now (delta spec 2.3.1): the rest of a
  // telegram coming in at the old one is distorted, so the frame open now is cut here.
  Entry& in = timeline_[current];
  if (in.decode && in.segment.period != unit_.bit_period()) cut(in, now);
  for (std::size_t i = current + 1; i < timeline_.size(); ++i) take(timeline_[i]);
  plan_reports();
  plan_monitor();
  recactn_.replan();
}

// --- reports to the telegram processor ---------------------------------------------------

// One event: the earliest report the telegram processor wants in its present state. A
// report whose time passes while it is not wanted is dropped: the processor would have
// done nothing with it.
bool SerialReceiver::candidate(Entry& e, FrameState& st, std::size_t i, bool telegram,
                               sim::Time now, sim::Time before) {
  bool& done = telegram ? st.end_done : st.start_done;
  if (done) return false;
  if (!(telegram ? static_cast<bool>(on_telegram_) : static_cast<bool>(on_start_))) {
    done = true;
    return false;
  }
  // Cheap refusals first: both reports come after the frame's start (so not in the past
  // when it is at or after `before`), and most frames pass a chip that wants neither.
  if (st.start >= before) return false;
  const auto report_time = [&] {
    if (!st.reports_known) work_out_reports(e, i);
    return telegram ? st.telegram_report : st.start_report;
  };
  const wire::DecodedFrame& f = e.decode->frames[i];
  if (!(telegram ? wants_telegram(st.start, f) : wants_start(st.start, f.address))) {
    // Dropped for good once its time has passed, so later plans do not ask again (the
    // time is only worked out for a frame already over, and not at all when it ended
    // longer ago than any report lags: a start report without a whole address, which
    // never comes, is dropped then too).
    if (st.end < now && (surely_over(e, st, now) || report_time() < now)) done = true;
    return false;
  }
  const sim::Time t = report_time();
  if (t < now || t == kNever) {
    done = true;
    return false;
  }
  return t < before;
}

inline void SerialReceiver::scan(Entry& e, sim::Time now, Report& best, bool fresh) {
  FrameState* st = e.frames.data();
  for (std::size_t i = 0, n = e.frames.size(); i < n; ++i, ++st) {
    if (st->start_done && st->end_done) continue;  // most frames a plan sees
    if (!fresh && st->reports_known && (st->start_done || st->start_report < now) &&
        (st->end_done || st->telegram_report < now)) {
      continue;  // nothing to come: a past report is never planned, done or not
    }
    if (candidate(e, *st, i, false, now, best.when)) {
      best = Report{st->start_report, e.serial, i, false};
      // A fresh frame's detection comes no earlier than its start report, and asking would
      // change nothing (it is not past) while there is a handler for it.
      if (fresh && on_telegram_) continue;
    }
    if (candidate(e, *st, i, true, now, best.when)) {
      best = Report{st->telegram_report, e.serial, i, true};
    }
  }
}

void SerialReceiver::plan_reports() {
  refresh_interest();
  const sim::Time now = scheduler_.now();
  // Mostly (a change in what the processor waits for) every report is past: what the walk
  // would find, without it.
  if (lazy_.empty() && !report_armed_ && all_past(now)) return;
  plan_by_walk(now);
}

void SerialReceiver::plan_by_walk(sim::Time now) {
  if (!lazy_.empty() && lazy_report_due(now)) absorb_lazy();
  Report best{kNever, 0, 0, false};
  if (unit_.running() && (on_start_ || on_telegram_)) {
    for (Entry& e : timeline_) {
      if (e.segment.since > best.when) break;  // in time order: the rest start later still
      if (e.decode && !all_past(e, now)) scan(e, now, best, false);
    }
  }
  const bool same = report_armed_ && best.when == report_.when && best.serial == report_.serial &&
                    best.frame == report_.frame && best.telegram == report_.telegram;
  if (same) return;
  cancel_report();
  report_ = best;
  if (best.when == kNever) return;
  arm(best);
}

// Inline in announce(): the usual read takes consider_one() without a call.
inline void SerialReceiver::consider(Entry& e) {
  if (!e.decode || !(on_start_ || on_telegram_)) return;
  if (!report_armed_ && e.frames.size() == 1 && on_start_ && on_telegram_) {
    return consider_one(e, HopTry::Full);  // the usual read: one frame, nothing planned
  }
  consider_more(e);
}

void SerialReceiver::consider_more(Entry& e) {
  const sim::Time planned = report_armed_ ? report_.when : kNever;
  if (planned <= e.segment.since) return;  // its reports all come after the planned one
  const sim::Time now = scheduler_.now();
  Report best{planned, 0, 0, false};
  scan(e, now, best, true);
  if (best.serial == 0) return;  // the planned report stays the earliest
  cancel_report();
  arm(best);
}

// What scan() finds for a fresh entry of one frame with nothing planned and both handlers:
// the frame starts at or after now (announce() refuses the past), so neither of its reports
// is past; the start report is taken when wanted and the address is whole, else the
// detection when wanted. Always inline in announce(): as a call of its own (GCC kept it
// out of line) its entry and exit cost about 18 instructions a read.
[[gnu::always_inline]] inline void SerialReceiver::consider_one(Entry& e, HopTry known) {
  FrameState& st = e.frames[0];
  const wire::DecodedFrame& f = e.decode->frames[0];
  if (known != HopTry::ReadTelegram) {
    if (known == HopTry::ReadStart || wants_start(st.start, f.address)) {
      reports_of(e, 0);
      if (st.start_report != kNever) return arm(Report{st.start_report, e.serial, 0, false});
      st.start_done = true;  // no whole address: never comes
    }
    if (!wants_telegram(st.start, f)) return;
  }
  // Mostly an MST: its start report (not wanted now) is worked out only if asked for later.
  if (!st.telegram_known) telegram_report_of(e, 0);
  arm(Report{st.telegram_report, e.serial, 0, true});
}

// The report event for `r`, none pending: the owned slot of its kind. Both slots are idle
// (report_armed_ is false at every call: the slot of a planned report is pending only while
// it is set) and no report planned is past (each caller takes reports at or after now), so
// the scheduler's tests are left out (asserted in debug builds).
inline void SerialReceiver::arm(const Report& r) {
  assert(!report_armed_);
  report_ = r;
  const sim::Scheduler::OwnedSlot slot = r.telegram ? telegram_report_event_ : start_report_event_;
  scheduler_.arm_owned_idle(slot, r.when);
  report_armed_ = true;
}

template <bool kTelegram>
void SerialReceiver::fire_report() {
  report_armed_ = false;
  Entry& back = timeline_.back();
  if (back.serial == report_.serial && report_.frame == 0 && back.frames.size() == 1 &&
      back.decode != nullptr) [[likely]] {
    if constexpr (kTelegram) {
      return fire_telegram_of_only(back);
    } else {
      return fire_start_of_only(back);
    }
  }
  fire_found<kTelegram>();
}

// fire_report() of any other report: its entry found by its serial.
template <bool kTelegram>
void SerialReceiver::fire_found() {
  const Report r = report_;
  Entry* e = find(r.serial);
  if (e == nullptr || !e->decode || r.frame >= e->frames.size()) return plan_reports();
  const wire::DecodedFrame& f = e->decode->frames[r.frame];
  FrameState& st = e->frames[r.frame];
  const sim::Time start = st.start;
  if constexpr (kTelegram) {
    st.end_done = true;
    {
      const Firing firing(*this, r.serial);
      on_telegram_(ReceivedTelegram{start, st.end, r.when, e->segment.period, f});
    }
    if (done_after_detection(r)) return;
  } else {
    st.start_done = true;
    {
      const Firing firing(*this, r.serial);
      on_start_(start, f.address);
    }
    refresh_interest();
    if (plan_telegram_after_start(r)) return;
  }
  plan_reports();
}

// What fire_report<false>() does with the usual report; plan_telegram_after_start() finds
// the entry again as the last one, mostly.
inline void SerialReceiver::fire_start_of_only(Entry& last) {
  const std::uint64_t serial = last.serial;
  {
    FrameState& st = last.frames.only();
    st.start_done = true;
    const Firing firing(*this, serial);
    on_start_(st.start, last.decode->frames[0].address);
  }
  refresh_interest();
  Entry& e = timeline_.back();  // the handler may have added entries (and moved them)
  if (e.serial == serial && e.frames.size() == 1 && e.decode != nullptr && on_telegram_ &&
      unit_.running()) [[likely]] {
    FrameState& st = e.frames.only();
    if (st.end_done || !wants_telegram(st.start, e.decode->frames[0])) return plan_reports();
    if (!st.telegram_known) telegram_report_of(e, 0);
    const sim::Time t = st.telegram_report;
    if (t < scheduler_.now() || t == kNever || report_armed_) return plan_reports();
    return arm(Report{t, serial, 0, true});
  }
  after_start(serial);
}

void SerialReceiver::after_start(std::uint64_t serial) {
  if (plan_telegram_after_start(Report{0, serial, 0, false})) return;
  plan_reports();
}

// What fire_report<true>() does with the usual report.
inline void SerialReceiver::fire_telegram_of_only(Entry& last) {
  const std::uint64_t serial = last.serial;
  {
    FrameState& st = last.frames.only();
    st.end_done = true;
    const Firing firing(*this, serial);
    on_telegram_(ReceivedTelegram{st.start, st.end, report_.when, last.segment.period,
                                  last.decode->frames[0]});
  }
  if (done_after_detection(Report{0, serial, 0, true})) return;
  plan_reports();
}

// After the detection `fired`: true when a plan would find nothing (nothing_after_detection,
// without the walk); then the last entry's frames are over for good once no change can cut
// the burst any more: nothing asks for them again (RECACT is asked from now on, past reports
// are never planned), so the entry stays as a burst not taken, which prunes and plans pass
// at once. False: the caller plans.
inline bool SerialReceiver::done_after_detection(const Report& fired) {
  refresh_interest();  // first: fewer values kept across the walk's calls (a plan asks again)
  const sim::Time now = scheduler_.now();
  Entry* const last = nothing_after_detection(fired, now);
  if (last == nullptr) return false;
  if (last->cut <= now) {
    last->decode = nullptr;
    last->frames.clear();
  }
  return true;
}

// After the detection of a burst's only frame, mostly the last burst announced: no report of
// an entry before is still to come, nor the frame's start report, so a plan would find
// nothing (a walk of the entries before, all past, says so more cheaply than a plan).
// The walk drops those entries as it goes, as prune() would now: the fired entry is in
// force, and one with no report to come, none planned (report_armed_) and none firing (the
// handler has returned) is done with. The next read's prune and an own telegram's settle
// then find the fired entry alone.
inline SerialReceiver::Entry* SerialReceiver::nothing_after_detection(const Report& fired,
                                                                      sim::Time now) {
  if (!lazy_.empty() || report_armed_ || fired.frame != 0) return nullptr;
  Entry& last = timeline_.back();
  if (last.serial != fired.serial || !last.decode || last.frames.size() != 1) return nullptr;
  const FrameState& st = last.frames[0];
  if (!st.end_done || (!st.start_done && !start_report_past(last, st, now))) return nullptr;
  while (&timeline_.front() != &last) {
    if (!all_past(timeline_.front(), now)) return nullptr;  // no frames: not taken (past)
    timeline_.pop_front();                                  // the others stay where they are
  }
  return &last;
}

// At the detection of e's only frame (now): its start report is past, or never comes (a
// plan finds nothing in it either way). Not worked out (a frame read for its detection
// only), the address is in at most 17 bits after the frame's start (opening flag, address,
// one stuffed 0), and its report comes before the detection when that is at least one MCLK
// period (the longest gap between edges) before the end: a later edge of the same
// pipeline. Otherwise false, and the caller's plan decides.
inline bool SerialReceiver::start_report_past(const Entry& e, const FrameState& st,
                                              sim::Time now) const {
  if (st.reports_known) return st.start_report < now;
  return st.start + 17 * e.segment.period + mclk_.period() <= st.end && st.telegram_known &&
         st.telegram_report <= now;
}

// After a frame's start report, the earliest report a plan can find is that frame's
// detection when the processor wants it: every report of an entry before comes before the
// frame's start (frames do not overlap, and the pipeline keeps their order), every other
// report of this entry or a later one (the lazy bursts too) after its end. So it is
// planned without the walk, as plan_reports() would plan it; otherwise the walk decides.
inline bool SerialReceiver::plan_telegram_after_start(const Report& fired) {
  if (!on_telegram_ || !unit_.running()) return false;
  Entry* e = find(fired.serial);  // again: the handler may have added entries (and moved them)
  if (e == nullptr || !e->decode || fired.frame >= e->frames.size()) return false;
  FrameState& st = e->frames[fired.frame];
  if (st.end_done) return false;
  if (!wants_telegram(st.start, e->decode->frames[fired.frame])) return false;
  const sim::Time t = telegram_report(*e, fired.frame);
  if (t < scheduler_.now() || t == kNever || report_armed_) return false;
  arm(Report{t, fired.serial, fired.frame, true});
  return true;
}

// --- line monitor ---------------------------------------------------------------------------

// The monitor hears a change only when it leaves or enters a bad signal: between good
// signals (edges at the receiver's rate) its status cannot change.
void SerialReceiver::plan_monitor() {
  absorb_lazy();
  scheduler_.cancel(monitor_event_);
  monitor_event_ = {};
  if (!unit_.running()) return;
  const sim::Time now = scheduler_.now();
  // Compared with what the monitor last took, not with the entry before: a change at the
  // very instant of the one in force replaces it in the timeline.
  RxdSegment before = monitor_last_;
  for (const Entry& e : timeline_) {
    if (e.serial <= monitor_seen_) continue;
    const bool quiet = good(before) && good(e.segment);
    if (e.segment.since > now) {
      if (quiet) {
        before = e.segment;
        continue;
      }
      monitor_event_ = scheduler_.at(
          e.segment.since, [](void* self) { static_cast<SerialReceiver*>(self)->fire_monitor(); },
          this);
      return;
    }
    monitor_seen_ = e.serial;
    monitor_last_ = e.segment;
    if (!quiet) unit_.monitor().input_changed(before, e.segment);
    before = e.segment;
  }
}

void SerialReceiver::fire_monitor() {
  monitor_event_ = {};
  plan_monitor();
}

// --- RECACT / RECACTN -----------------------------------------------------------------------

// Low from the first frame's opening flag to the end of the last frame (or the cut). A
// telegram cut by the next one keeps it low across the seam.
bool SerialReceiver::recact_at(sim::Time t) const {
  absorb_lazy_to_read();
  if (!unit_.running()) return false;
  const Entry& e = timeline_[in_force(t)];
  if (!e.decode || e.frames.empty()) return false;
  return e.frames[0].start <= t && t < e.frames.back().end;
}

sim::Time SerialReceiver::next_change_after(sim::Time t) const {
  absorb_lazy_to_read();
  const bool level = recact_at(t);
  std::vector<sim::Time> candidates;
  for (std::size_t i = in_force(t); i < timeline_.size(); ++i) {
    const Entry& e = timeline_[i];
    candidates.push_back(e.segment.since);
    if (e.decode && !e.frames.empty()) {
      candidates.push_back(e.frames[0].start);
      candidates.push_back(e.frames.back().end);
    }
  }
  std::sort(candidates.begin(), candidates.end());
  for (const sim::Time c : candidates) {
    if (c > t && recact_at(c) != level) return c;
  }
  return kNever;
}

}  // namespace sercon::chip

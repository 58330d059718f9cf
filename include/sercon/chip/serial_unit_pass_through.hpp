// The repeater's and TxD's stages of a burst passing a node, inline: those of a lazy hop
// (docs/serial-and-ring.md, "Lazy hops") for SerialReceiver::try_lazy_hop and their
// absorbing later, the repeater's forward time, and the repeater's input and TxD's line_burst for a
// burst the node reads (SerialReceiver::pass_to_repeater). Asked at every hop (~32 000 a cycle with
// 254 slaves), where a call per stage costs as much as its checks. And an own telegram's way
// through the repeater (SerialRepeater::own, with its usual absorb: settle_lazy), inline in
// SerialTransmitter::send.
#pragma once

#include <cassert>

#include "sercon/chip/chip.hpp"
#include "sercon/chip/serial_unit.hpp"
#include "sercon/chip/serial_unit_outputs.hpp"
#include "sercon/chip/serial_unit_receiver.hpp"
#include "sercon/chip/serial_unit_receiver_inline.hpp"
#include "sercon/chip/serial_unit_repeater.hpp"

namespace sercon::chip {

// write_burst() of the bits a burst holds (never null): counted up without operator='s
// tests (SharedBits::assign_held). At every burst a line books.
inline void write_held_burst(RxdSegment& s, sim::Time since, sim::Time period,
                             const SharedBits& bits) {
  s.is_burst = true;
  s.condition = LineCondition::Idle;
  s.since = since;
  s.period = period;
  s.bits.assign_held(bits);
}

// append_burst() of a burst's bits (never null) that do not live in `line` (so the append
// cannot move them): written into the new slot by write_held_burst().
template <class Line>
inline void append_held_burst(Line& line, sim::Time since, sim::Time period,
                              const SharedBits& bits) {
  write_held_burst(line.emplace_back(), since, period, bits);
}

inline sim::Time SerialRepeater::forward_time(sim::Time t) const {
  const sim::Time sclk = sclk_period_;
  const sim::Time due = t + SerialUnit::kRepeaterDelayBits * unit_.bit_period();
  if (due <= 0) return (due + sclk - 1) / sclk * sclk;  // before time 0: not on a ring
  return static_cast<sim::Time>(by_sclk_.divide(static_cast<std::uint64_t>(due + sclk - 1))) * sclk;
}

inline void SerialRepeater::input(const RxdSegment& segment) {
  if (!repon_ || unit_.bit_period() == 0) return;
  const sim::Time at = forward_time(segment.since);
  if (segment.is_burst && forward_unbooked_ && forward_unbooked(segment, at)) return;
  input_booked(segment, at);
}

inline bool SerialRepeater::input_handing(const RxdSegment& segment, Handed& handed) {
  if (!repon_ || unit_.bit_period() == 0) return false;
  const sim::Time at = forward_time(segment.since);
  if (segment.is_burst && forward_unbooked_ && hand_unbooked(segment, at, handed)) return true;
  input_booked(segment, at);
  return false;
}

inline bool SerialRepeater::hand_read(const RxdSegment& segment, sim::Time at, Handed& handed) {
  if (hand_unbooked(segment, at, handed)) return true;
  input_booked(segment, at);
  return false;
}

inline void SerialRepeater::input_booked(const RxdSegment& segment, sim::Time at) {
  absorb_forwarded();
  // The later word wins (line.hpp).
  drop_announced_from(background_, at);
  prune();
  RxdSegment& out = background_.emplace_back();
  out = segment;
  out.since = at;
  if (own_.empty()) {  // nothing of its own in the way: straight on (the usual case)
    if (out.is_burst) return unit_.outputs().line_burst(out.burst());
    return unit_.outputs().line_condition(at, out.condition, out.period);
  }
  emit_from(at);
}

// The lone follower (a plain fibre) takes the burst by pass_through when it can, and this
// delivers it to the listener behind: the follower books it only when asked (book_all).
inline void TxdOutputs::line_burst(const LineBurst& burst) {
  book_own();
  prune();
  const bool dropped = drop_from(burst.start);
  LineListener* const only = lone_follower_;
  LineListener* next = nullptr;
  const LineBurst* out = nullptr;
  const bool passed = pass_unbooked_ && only != nullptr && follower_takes(burst, next, out);
  if (passed) {
    follower_delay_ = out->start - burst.start;
  } else if (unbooked_ > 0) {
    book_unbooked();  // booked before what it is told now
  }
  append_held_burst(line_, burst.start, burst.bit_period, burst.bits);
  if (passed) {
    ++unbooked_;  // first: what `next` is told may come back round to this line
    next->line_burst(*out);
  } else if (only != nullptr) {  // the usual case: one fibre behind the node
    only->line_burst(burst);
  } else {
    tell_followers(burst);
  }
  // The back is the burst: the line lights up only if it was dark before.
  if (dropped || line_.size() < 2 || is_dark(line_[line_.size() - 2])) plan_pins();
}

inline void TxdOutputs::own_burst(const LineBurst& own, sim::Time end) {
  // What line_burst() would do here, without its prune, drop and plan of the pins (a line of
  // one lit segment before the telegram) or keeping it: the own telegram stays in the
  // repeater's queue until the line takes it (book_own).
  if (own_unbooked_ == nullptr && line_.size() == 1) {
    const RxdSegment& last = line_.back();
    if (last.since < own.start && !is_dark(last)) return own_lit(own, end);
  }
  line_burst(own);
}

inline void TxdOutputs::own_lit(const LineBurst& own, sim::Time end) {
  if (pass_unbooked_ && lone_link_ != nullptr) {
    LineListener* next = nullptr;
    const LineBurst* out = nullptr;
    if (lone_link_->pass_checked(own, *this, next, out)) {
      follower_delay_ = out->start - own.start;
      own_unbooked_ = &own;  // first: what `next` is told may come back round to this line
      own_unbooked_end_ = end;
      return next->line_burst(*out);
    }
  }
  line_burst(own);
}

// A read hop's burst handed on unbooked when the repeater's and TxD's conditions allow
// (would_pass) and the lone follower takes it.
inline bool SerialRepeater::forward_unbooked(const RxdSegment& segment, sim::Time at) {
  Handed handed;
  if (!hand_unbooked(segment, at, handed)) return false;
  // A copy for whatever may absorb (drop) the forwarded bursts before it has read them:
  // this node (its TxD back to its own RxD), or a listener that is not a receiver.
  if (handed.receiver == nullptr || handed.receiver == &unit_.receiver()) {
    const LineBurst copy = *handed.out;
    return handed.next->line_burst(copy), true;
  }
  handed.next->line_burst(*handed.out);
  return true;
}

inline bool SerialRepeater::hand_unbooked(const RxdSegment& segment, sim::Time at, Handed& handed) {
  if (!would_pass_on(at)) return false;  // input() has asked for REPON and the rate
  const sim::Time now = scheduler_.now();
  TxdOutputs& txd = unit_.outputs();
  // Kept as it reaches TxD's listener, and handed on from here (built in its slot, every
  // field set: the queue goes by drop_front(), its slots reused as they are).
  Forwarded& kept = forwarded_.reuse_back();
  kept.leaves = at;
  kept.reaching.bit_period = segment.period;
  kept.reaching.bits.assign_held(segment.bits);  // a burst: it has bits
  kept.reaching.start = at;  // set by the listener; set here too, so the entry is whole
  if (!txd.follower_takes_into(at, kept.reaching, handed.next, handed.receiver)) {
    forwarded_.pop_back();
    return false;
  }
  const sim::Time delay = kept.reaching.start - at;
  txd.set_follower_delay(delay);
  while (forwarded_.size() > 1 && forwarded_[1].leaves + delay <= now) forwarded_.drop_front();
  handed.out = &kept.reaching;  // the last: not dropped
  return true;
}

// Inline: at every own telegram (SerialTransmitter::send), a call less.
inline void SerialRepeater::own(LineBurst&& telegram, sim::Time end, sim::Time now) {
  // absorb_passed(), its usual case inline: the lazy burst settles, which leaves nothing
  // forwarded and nothing for prune() to drop (settle()).
  if (unit_.receiver().absorb_lazy_for_own(now)) return own_settled(std::move(telegram), end);
  absorb_forwarded();
  prune(now);  // first: the telegram itself is not over (it begins at or after now)
  // TxD's line takes the last own telegram before its slot may be reused below (mostly the
  // settle has dropped it: over).
  unit_.outputs().book_own();
  const LineBurst& burst = keep_own(std::move(telegram), end);
  // The only own telegram not yet over (the usual case): what emit_from(burst.start) does,
  // without its walk. The telegram; then, when nothing of the background begins after its
  // start, the background segment in force where it ends (joined half-way unless it begins
  // there); else emit_from() from its end, as emit_from(burst.start) goes on.
  if (own_.size() == 1 && !background_.empty()) {
    unit_.outputs().own_burst(burst, end);
    return own_after(burst, end);
  }
  emit_from(burst.start);
}

// own() right after a settle (a slave's usual case): the line and TxD's hold the settled
// burst alone, and nothing forwarded, no own telegram and nothing of TxD's unbooked is left
// (settle()). So book_own() has nothing to book, and own_burst()'s tests of the line come
// out true but for the link's (TxdOutputs::own_lit) when the burst began before the
// telegram.
// When nothing came back round to the line meanwhile (it holds the settled burst alone) and
// the telegram goes at that burst's rate, own()'s idle fill where it ends is a no-op
// (line_condition(): the line's last segment, booked or not, is the telegram). Held to
// own() by the lazy-hops-on/off ring tests (with lazy hops off nothing settles).
inline void SerialRepeater::own_settled(LineBurst&& telegram, sim::Time end) {
  const LineBurst& kept = keep_own(std::move(telegram), end);  // own_ was empty
  // The settled burst mostly began before now; a fibre of no delay lets it begin now.
  if (background_.front().since < kept.start) {
    unit_.outputs().own_lit(kept, end);
  } else {
    unit_.outputs().own_burst(kept, end);
  }
  if (background_.size() == 1 && own_.size() == 1 && background_.front().period == kept.bit_period)
    return;
  own_after(kept, end);
}

// The telegram as kept: only own() pushes to own_, and the chain that line_burst() starts
// sends nothing, so the slot holds it throughout (a prune leaves a slot as it is).
inline const LineBurst& SerialRepeater::keep_own(LineBurst&& telegram, sim::Time end) {
  LineBurst& kept = own_.reuse_back();  // every field set (own_ goes by drop_front())
  kept.start = telegram.start;
  kept.bit_period = telegram.bit_period;
  kept.bits = std::move(telegram.bits);  // no count up and down
  own_end_ = end;
  return kept;
}

// own() after TxD has the telegram: the background in force where it ends (see own()).
inline void SerialRepeater::own_after(const LineBurst& burst, sim::Time end) {
  if (own_.size() == 1 && background_.back().since <= burst.start) {
    // Joined half-way (it begins before the telegram's end): emit_background's last case,
    // here without the call (mostly the idle fill the line is in anyway, a no-op).
    const RxdSegment& s = background_.back();
    if (s.since != end) return unit_.outputs().line_condition(end, s.condition_at_join(), s.period);
    return emit_background(end, background_.size() - 1, false);
  }
  emit_from(end);
}

inline void SerialRepeater::absorb_passed() {
  // The own telegram TxD's line left out first (it came before everything passed on since).
  unit_.outputs().book_own();
  unit_.receiver().absorb_lazy();  // its repeater stage absorbs forwarded_ first
  absorb_forwarded();
}

inline void SerialRepeater::absorb(sim::Time leaves, sim::Time period, const SharedBits& bits) {
  // The forwarded bursts first (earlier than the receiver's lazy ones). Mostly (an own
  // telegram absorbs) this burst has reached TxD's listener by now, so every one of them is
  // over: absorb_forwarded_now()'s first case, here without the call.
  if (!forwarded_.empty()) {
    if (leaves + unit_.outputs().follower_delay() <= scheduler_.now()) {
      forwarded_.drop_all();
    } else {
      absorb_forwarded_now(leaves);
    }
  }
  book(leaves, period, bits);
}

inline void SerialRepeater::book(sim::Time leaves, sim::Time period, const SharedBits& bits) {
  if (!background_.empty()) expect_absorbed_in_order("repeater", background_.back().since, leaves);
  prune();
  append_held_burst(background_, leaves, period, bits);
  unit_.outputs().absorb(leaves, period, bits);
}

inline void TxdOutputs::absorb(sim::Time start, sim::Time period, const SharedBits& bits) {
  book_own();
  expect_absorbed_in_order("TxD", line_.back().since, start);
  prune();
  append_held_burst(line_, start, period, bits);
  ++unbooked_;  // it took the burst by pass_through: booked when it asks (book_all)
}

// The slot of a line (repeater, TxD) to be set to a settled burst alone: what a prune would
// leave once the burst, appended, is in force. The front slot, written over (no append);
// those after it go as drop_front() lets them (their bits until the slot is used again).
template <class Line>
inline RxdSegment& settled_slot(Line& line) {
  while (line.size() > 1) line.drop_front();
  return line.front();  // the line is never empty (it holds what is in force)
}

inline void TxdOutputs::settle(sim::Time start, sim::Time period, SharedBits&& bits) {
  own_unbooked_ = nullptr;  // before the burst (last_since()): over, as settled_slot() drops it
  write_burst(settled_slot(line_), start, period, std::move(bits));
  unbooked_ = 1;  // it took the burst by pass_through; those before went unbooked (prune())
}

inline bool SerialRepeater::settles(sim::Time leaves, sim::Time now) const {
  // The burst has reached TxD's listener (so the forwarded bursts are over, absorb()), no
  // own telegram is left (prune()), and it comes after what the line and TxD's hold.
  const TxdOutputs& txd = unit_.outputs();
  return leaves + txd.follower_delay() <= now && own_end_ <= now && !background_.empty() &&
         background_.back().since < leaves && txd.last_since() < leaves;
}

// `bits` are taken: the last line gets them (no count up and down).
inline void SerialRepeater::settle(sim::Time leaves, sim::Time period, SharedBits&& bits) {
  forwarded_.drop_all();
  own_.drop_all();
  write_held_burst(settled_slot(background_), leaves, period, bits);
  unit_.outputs().settle(leaves, period, std::move(bits));
}

// --- the receiver's lazy bursts absorbed (SerialReceiver::absorb_waiting, and inline for an
// own telegram: SerialRepeater::own) ---------------------------------------------------------

inline void SerialReceiver::prune_lazy(sim::Time now) {
  if (lazy_.size() > 1 && lazy_[1].reaches() <= now) drop_lazy_over(now);  // mostly not
}

// Lazy bursts over at every stage of this node: the next one is in force at TxD (so at
// RxD too) and at the next receiver (the fibre would drop this one from its history when it
// books them), and this one's reports would be past. The full path would have
// dropped them.
// Called when the second one has reached the next receiver (prune_lazy asks that first).
inline void SerialReceiver::drop_lazy_over(sim::Time now) {
  do {
    const LazyBurst& front = lazy_.front();
    if (front.reports_over >= now) return;
    lazy_.drop_front();
  } while (lazy_.size() > 1 && lazy_[1].reaches() <= now);
}

// A lazy burst in force by now, every entry before it done with: prune() would leave it
// alone once appended, so it takes the front's place at once (its entry as append() would
// make it, written in place), the others dropped from the back, none moved. `over`: it has
// ended and its reports are past (the usual absorb, an own telegram's), so nothing can ask
// for its frames any more (RECACT is asked from now on, reports past are never planned):
// it is kept without them, as a burst not taken, which the prunes and plans pass at once.
inline void SerialReceiver::take_in_front(const LazyBurst& lazy, bool over) {
  while (holds_more_than(1)) timeline_.pop_back();
  Entry& e = timeline_.front();
  write_held_burst(e.segment, lazy.arrived, lazy.reaching.bit_period, lazy.reaching.bits);
  e.cut = lazy.ends;  // the segment's burst_end()
  e.serial = next_serial_++;
  if (over) {
    e.decode = nullptr;
    e.frames.clear();
    return;
  }
  take(e, true);
}

// Mostly (an own telegram absorbs the burst that came before it) one burst waits, and it has
// reached the next receiver: it is in force at every stage of the node and at the far end,
// so each timeline would hold just it once pruned. Each is set to that at once (settle),
// without the general booking's prunes and appends. False: absorb_waiting() books them.
// Only that it has reached the next receiver and the entries' reports are left to ask: it
// came after the timeline's last entry and the repeater's settles() held when it hopped
// (try_lazy_hop: would_pass(), or after the lazy burst before it), and nothing has changed
// the timeline, the repeater or TxD since (every way into them absorbs the lazy bursts
// first). Having reached the next receiver, it has reached TxD's listener: TxD's follower
// delay is the one it hopped with (set at the first hop of a run, the same for the rest).
inline bool SerialReceiver::settle_lazy(sim::Time now) {
  prune_lazy(now);  // a burst over by now would only be pruned
  if (lazy_.size() != 1) return false;
  LazyBurst& lazy = lazy_.front();
  if (lazy.reaches() <= now && all_done_with(now)) {
    SerialRepeater& repeater = unit_.repeater();
    // What the hop made sure of, and nothing has changed since (checked in debug builds).
    assert(timeline_.back().segment.since < lazy.arrived && repeater.settles(lazy.leaves, now));
    take_in_front(lazy, lazy.reports_over < now);
    // Its bits go to TxD's line: the slot is let go at once (drop_all).
    repeater.settle(lazy.leaves, lazy.reaching.bit_period, std::move(lazy.reaching.bits));
    lazy_.drop_all();
    return true;
  }
  return false;
}

inline bool SerialReceiver::absorb_lazy_for_own(sim::Time now) {
  if (lazy_.empty()) return false;
  if (settle_lazy(now)) return true;
  absorb_waiting();
  return false;
}

inline bool TxdOutputs::would_pass(sim::Time leaves) const {
  // Nothing announced at or after it to drop, and no change between dark and light (the
  // pins' plan stays as it is): what line_burst() would do is only to keep it.
  if (lone_follower_ == nullptr) return false;
  if (own_unbooked_ != nullptr) return own_unbooked_->start < leaves;  // the last segment, lit
  const RxdSegment& last = line_.back();
  return last.since < leaves && (last.is_burst || last.condition != LineCondition::Dark);
}

inline bool SerialRepeater::would_pass(sim::Time leaves) const {
  return repon_ && unit_.bit_period() != 0 && would_pass_on(leaves);
}

inline bool SerialRepeater::would_pass_on(sim::Time leaves) const {
  // What prune() would leave: no own telegram not yet over (they end in order), and the
  // background never pruned empty. Nothing is kept, so nothing needs pruning here.
  if (own_end_ > scheduler_.now()) return false;
  // After read hops' bursts forwarded unbooked TxD holds as it did for those: only its
  // listener is left to ask.
  if (!forwarded_.empty()) return forwarded_.back().leaves < leaves;
  if (background_.empty() || background_.back().since >= leaves) return false;
  return unit_.outputs().would_pass(leaves);
}

}  // namespace sercon::chip

// A link that passes every burst on unchanged after a fixed delay to one listener (a whole
// fibre without bit errors: ring::Fibre), kept as data so that a chip's TxD takes a burst
// through it inline (LineListener::pass_through's work, without a call): at every hop a
// telegram makes (docs/serial-and-ring.md, "Lazy hops").
#pragma once

#include "sercon/chip/line.hpp"
#include "sercon/sim/scheduler.hpp"

namespace sercon::chip {

class PlainLink {
 public:
  explicit PlainLink(const sim::Scheduler& scheduler, sim::Time delay)
      : scheduler_(scheduler), delay_(delay) {}
  PlainLink(const PlainLink&) = delete;
  PlainLink& operator=(const PlainLink&) = delete;

  // LineListener::pass_through: when the link is plain, the burst as it reaches `next`.
  // Bursts of another sender still waiting to be booked: refused (they take the full path,
  // which books them).
  bool pass(const LineBurst& burst, PassedBursts& sender, LineListener*& next,
            const LineBurst*& out) {
    if (!burst.bits || burst.bit_period <= 0 || burst.start < scheduler_.now()) return false;
    return pass_checked(burst, sender, next, out);
  }
  // pass() for a burst known to have bits and a bit period, at or after now: a chip's TxD
  // hands on only what it was announced, and that was checked where it came in. Always
  // inline: with two own-telegram paths (TxdOutputs::own_lit) GCC made it a call.
  [[gnu::always_inline]] bool pass_checked(const LineBurst& burst, PassedBursts& sender,
                                           LineListener*& next, const LineBurst*& out) {
    if (!plain_) return false;
    if (passed_from_ != &sender && passed_from_ != nullptr) return false;  // mostly the same sender
    passed_from_ = &sender;
    passed_.start = last_passed_ = burst.start + delay_;
    passed_.bit_period = burst.bit_period;
    passed_.bits.assign_held(burst.bits);
    next = output_;
    out = &passed_;
    return true;
  }
  // pass_checked() for a sender that keeps the burst as it reaches `next` itself (a lazy
  // hop): only when it arrives there, the burst leaving at `leaves`.
  bool pass_at(sim::Time leaves, PassedBursts& sender, LineListener*& next, sim::Time& arrives) {
    if (!plain_) return false;
    if (passed_from_ != &sender && passed_from_ != nullptr) return false;  // mostly the same sender
    passed_from_ = &sender;
    arrives = last_passed_ = leaves + delay_;
    next = output_;
    return true;
  }
  // pass_at() naming the output's receiver too (LineListener::receiver(), kept here: a chain
  // of lazy hops goes on there, a load less after the link).
  bool pass_at(sim::Time leaves, PassedBursts& sender, LineListener*& next, sim::Time& arrives,
               SerialReceiver*& receiver) {
    if (!pass_at(leaves, sender, next, arrives)) return false;
    receiver = output_receiver_;
    return true;
  }

  sim::Time delay() const { return delay_; }
  LineListener* output() const { return output_; }
  // Set by the owner: where it delivers, and whether it passes bursts on as they are (and
  // has somewhere to pass them).
  void set(LineListener* output, bool plain) {
    output_ = output;
    output_receiver_ = output != nullptr ? output->receiver() : nullptr;
    plain_ = plain && output != nullptr;
  }
  // Who holds the bursts passed and not yet booked (null: none), taken back; the owner asks
  // it to book them before it reads or adds to what it holds.
  PassedBursts* take_sender() {
    PassedBursts* s = passed_from_;
    passed_from_ = nullptr;
    return s;
  }
  // A burst booked (its start at the far end): the last one passed means all are.
  void booked(sim::Time start) {
    if (start == last_passed_) passed_from_ = nullptr;
  }

 private:
  const sim::Scheduler& scheduler_;
  sim::Time delay_;
  LineListener* output_ = nullptr;
  SerialReceiver* output_receiver_ = nullptr;  // output_->receiver()
  bool plain_ = false;
  PassedBursts* passed_from_ = nullptr;
  sim::Time last_passed_ = 0;  // the last burst passed: its start at the far end
  LineBurst passed_;           // the last one pass() handed on (its `out`)
};

}  // namespace sercon::chip

// The repeater (delta spec 2.3.3, REPON) and the line it feeds: what RxD receives goes on
// to TxD a fixed delay later (kRepeaterDelayBits bit times, rounded up to the SCLK grid),
// the same bits object, unchanged. It works on announcements (line.hpp): a telegram is
// passed on the moment the receiver is told of it, with the time it will leave TxD, so it
// costs no event. Own telegrams are inserted: while one is sent nothing received is passed
// on (a telegram beginning under it is lost whole), a repeated telegram in the way is cut
// where the own one begins (own telegram wins), and after it the line takes up the
// received signal again (a telegram half-way through counts as its idle fill). REPON = 0:
// only own telegrams and their idle fill leave. docs/serial-and-ring.md, "Repeater".
#pragma once

#include "sercon/chip/line.hpp"
#include "sercon/chip/serial_unit_input.hpp"
#include "sercon/sim/circular_queue.hpp"
#include "sercon/sim/reciprocal.hpp"
#include "sercon/sim/scheduler.hpp"
#include "sercon/sim/time.hpp"

namespace sercon::chip {

class SerialUnit;

class SerialRepeater {
 public:
  explicit SerialRepeater(SerialUnit& unit);

  void reset();
  void release();
  // RxD announced `segment` (segment.since >= now).
  inline void input(const RxdSegment& segment);  // serial_unit_pass_through.hpp
  // A burst handed on unbooked to TxD's lone follower, for the caller to deliver: `out` to
  // `next` (whose receiver() is `receiver`).
  struct Handed {
    LineListener* next = nullptr;
    SerialReceiver* receiver = nullptr;
    const LineBurst* out = nullptr;
  };
  // input() of a burst the receiver's loop reads (SerialReceiver::line_burst): true when it
  // goes on unbooked, left in `handed` (the chain goes on in that loop, not a call deeper);
  // false when done here.
  inline bool input_handing(const RxdSegment& segment, Handed& handed);
  // input_handing() of a burst a lazy hop's checks have found the repeater would take as it
  // is (SerialReceiver::read: REPON on at the unit's rate, forwarding unbooked), leaving at
  // `at` (its forward_time()).
  inline bool hand_read(const RxdSegment& segment, sim::Time at, Handed& handed);
  // The transmitter announced an own telegram (burst.start >= now) ending at `end` (its
  // end(), worked out once by the sender); its bits are taken. `now`: the scheduler's, as
  // the sender has it.
  [[gnu::always_inline]] inline void own(LineBurst&& telegram, sim::Time end,
                                         sim::Time now);  // serial_unit_pass_through.hpp
  // own() right after the settle of the burst before it (serial_unit_pass_through.hpp).
  [[gnu::always_inline]] inline void own_settled(LineBurst&& telegram, sim::Time end);
  // own() once TxD has the telegram: the background where it ends.
  [[gnu::always_inline]] inline void own_after(const LineBurst& burst, sim::Time end);
  // The telegram pushed to own_ (its bits taken), own_end_ set.
  [[gnu::always_inline]] inline const LineBurst& keep_own(LineBurst&& telegram, sim::Time end);
  // REPON or the bit rate changed.
  void refresh();

  // Lazy hops (docs/serial-and-ring.md): whether a burst leaving at `leaves`
  // (forward_time() of its start at RxD) would go straight on to TxD's lone follower (REPON
  // on, nothing of its own in the way or announced after it, and TxD's checks, or only the
  // follower's left after a read hop's burst forwarded unbooked); the receiver then hands
  // it to that follower, and absorb() takes it into the repeater's line (and TxD's) later,
  // as input() would have, telling no one. Inline (serial_unit_pass_through.hpp).
  inline bool would_pass(sim::Time leaves) const;
  // would_pass() for a caller that knows REPON on at a running rate.
  inline bool would_pass_on(sim::Time leaves) const;
  // The burst as it leaves (its start `leaves`; no LineBurst built for it).
  inline void absorb(sim::Time leaves, sim::Time period, const SharedBits& bits);
  // absorb() of a burst that has reached TxD's listener by now, after everything here:
  // whether the line and TxD's would then hold just it once pruned (settles), and so
  // set them (settle). Inline (serial_unit_pass_through.hpp).
  inline bool settles(sim::Time leaves, sim::Time now) const;
  [[gnu::always_inline]] inline void settle(sim::Time leaves, sim::Time period, SharedBits&& bits);
  // Before anything reads or changes the repeater or TxD: the bursts passed on and not yet
  // booked there (those of read hops, then the node's lazy ones) are booked.
  inline void absorb_passed();  // serial_unit_pass_through.hpp

  // Read hops forwarded unbooked (forward_unbooked), on unless lazy hops are switched off.
  void set_forward_unbooked(bool on) {
    if (!on) absorb_forwarded();
    forward_unbooked_ = on;
  }

  // Own telegrams in time order: those not yet over, perhaps after some over before now
  // (no time at or after now falls in those). The transmitter's IDLE asks them.
  const sim::CircularQueue<LineBurst>& own_telegrams() const { return own_; }
  // When something that reaches RxD at `t` leaves on TxD.
  inline sim::Time forward_time(sim::Time t) const;  // serial_unit_pass_through.hpp
  bool on() const { return repon_; }
  sim::Time sclk_period() const { return sclk_period_; }
  const sim::Reciprocal& by_sclk() const { return by_sclk_; }

 private:
  void take_up_received();  // REPON on: the received line from now on
  // A burst the receiver read (the full path) that would go straight on: handed to TxD's
  // listener at once and kept in forwarded_, booked here and in TxD only when something
  // looks (absorb_forwarded), as a lazy hop's. False: it takes the full path.
  // Always inline: GCC makes it a call (the chain it starts comes back into input()).
  [[gnu::always_inline]] inline bool forward_unbooked(const RxdSegment& segment, sim::Time at);
  // forward_unbooked() but for the delivery, left to the caller in `handed`.
  [[gnu::always_inline]] inline bool hand_unbooked(const RxdSegment& segment, sim::Time at,
                                                   Handed& handed);
  // input() past its unbooked case: the full path (the segment leaving at `at`).
  inline void input_booked(const RxdSegment& segment, sim::Time at);
  // `next`: when what is booked after them leaves (kNoneNext: not known).
  static constexpr sim::Time kNoneNext = INT64_MAX / 2;
  void absorb_forwarded(sim::Time next = kNoneNext) {
    if (!forwarded_.empty()) absorb_forwarded_now(next);
  }
  void absorb_forwarded_now(sim::Time next);
  // Into the line and TxD's, telling no one.
  inline void book(sim::Time leaves, sim::Time period, const SharedBits& bits);
  void prune() { prune(scheduler_.now()); }  // inline: at every burst
  void prune(sim::Time now) {
    // Own telegrams end in order: the last one over (the usual case) means all are.
    if (own_end_ <= now) {
      own_.drop_all();
    } else {
      while (!own_.empty() && own_.front().end() <= now) own_.drop_front();
    }
    drop_replaced_by(background_, now);
  }
  // Announces the line on TxD from `t` on: the received signal (or the own idle fill when
  // REPON = 0) with the own telegrams laid over it.
  void emit_from(sim::Time t);
  void emit_background(sim::Time at, std::size_t index, bool joined);

  SerialUnit& unit_;
  sim::Scheduler& scheduler_;  // the chip's: asked for now at every burst
  sim::Time sclk_period_;      // the grid a forwarded telegram leaves on (fixed by the config)
  sim::Reciprocal by_sclk_;    // divides by sclk_period_: asked at every hop a telegram makes
  bool repon_ = false;
  // What leaves TxD when no own telegram is in the way, in time order, the front in force
  // now: the received signal (REPON = 1, TxD times) or the own idle fill (REPON = 0).
  sim::CircularQueue<RxdSegment> background_;
  // Own telegrams not yet over, in time order. Pushed by reuse_back(), let go by drop_front()
  // and drop_all() (a slot keeps its bits until the push that reuses it).
  sim::CircularQueue<LineBurst> own_;
  // The end of the last own telegram (0 after a reset): while it is to come, own_ holds it
  // as its back; once past, nothing of its own is in the way (asked at every hop).
  sim::Time own_end_ = 0;
  // Read hops' bursts passed on (as they reach TxD's listener, and when they leave TxD) and not yet
  // booked, in time order, all after background_'s last. One whose successor has reached TxD's
  // listener by now goes unbooked: the repeater, TxD and the listener would have dropped it then.
  struct Forwarded {
    LineBurst reaching;  // as it reaches TxD's listener (the burst handed on)
    sim::Time leaves = 0;
  };
  // Pushed by reuse_back(), let go by drop_front() / drop_all() (a slot keeps its bits until
  // the push that reuses it, as the receiver's lazy bursts do).
  sim::CircularQueue<Forwarded> forwarded_;
  bool forward_unbooked_ = true;
};

}  // namespace sercon::chip

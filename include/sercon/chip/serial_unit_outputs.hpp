// TxD1-6: what each pin shows and what the fibre or bus behind it gets (datasheet Table 1:
// TxD1 data with high impedance; TxD2-6 data or parallel output port, each with individual
// high impedance; register 0x02 TXOE / TXLIGHT / TMODE, 0x0B PORTSEL / PORTVAL, 0x01 POLTXD).
//
// Listeners are told light: the line model carries what the fibre carries. POLTXD only
// decides which pin level is light (docs/serial-and-ring.md, "Polarity").
#pragma once

#include <array>

#include "sercon/chip/line.hpp"
#include "sercon/chip/plain_link.hpp"
#include "sercon/chip/serial_unit_input.hpp"
#include "sercon/sim/circular_queue.hpp"
#include "sercon/sim/scheduler.hpp"
#include "sercon/sim/signal.hpp"
#include "sercon/sim/time.hpp"

namespace sercon::chip {

class SerialUnit;

class TxdOutputs final : public PassedBursts {
 public:
  explicit TxdOutputs(SerialUnit& unit);
  ~TxdOutputs();
  TxdOutputs(const TxdOutputs&) = delete;
  TxdOutputs& operator=(const TxdOutputs&) = delete;

  // pin 1..6. A listener replaced or disconnected is told Dark at now (unless another pin
  // still drives it).
  void connect(unsigned pin, LineListener& listener);
  void disconnect(unsigned pin);

  // Announcements of the serial line (own telegrams, idle fill or the repeated signal) at
  // `at` / burst.start >= now; the later word wins (line.hpp). Announcing the condition the
  // line is in at `at` anyway, with nothing announced after it, is a no-op.
  void line_condition(sim::Time at, LineCondition condition, sim::Time period) {
    // Inline: the idle fill after each own telegram is such a no-op. What prune() would
    // drop goes at the next change (it never touches the last segment).
    if (own_unbooked_ != nullptr) {  // the line's last segment: the test below on it
      if (at >= own_unbooked_end_ && condition == LineCondition::Idle &&
          own_unbooked_->bit_period == period)
        return;
      book_own();
    }
    const RxdSegment& last = line_.back();
    if (last.since <= at) {
      const bool in_burst = last.is_burst && at < last.burst_end();
      const LineCondition c = last.is_burst ? LineCondition::Idle : last.condition;
      if (!in_burst && c == condition && last.period == period) return;
    }
    change_condition(at, condition, period);
  }
  // serial_unit_pass_through.hpp. Always inline: GCC made it a call at every own telegram.
  [[gnu::always_inline]] inline void line_burst(const LineBurst& burst);
  // line_burst() of the repeater's own telegram `own` (ending at `end`; an element of its queue of
  // own telegrams, kept there until the next one is pushed): when nothing is to be pruned or
  // dropped before it, the line is lit and the lone follower is a plain link that takes it,
  // the follower gets it unbooked and the line takes it only when something looks
  // (book_own), as it takes a lazy burst. Else line_burst(). Inline
  // (serial_unit_pass_through.hpp).
  [[gnu::always_inline]] inline void own_burst(const LineBurst& own, sim::Time end);
  // own_burst() once the line is known to be one lit segment begun before `own`, nothing
  // unbooked (as after settle()): only the link is left to ask (serial_unit_pass_through.hpp).
  [[gnu::always_inline]] inline void own_lit(const LineBurst& own, sim::Time end);
  // The own telegram own_burst() left out of the line, into it (first: before anything
  // reads or changes the line). Before the repeater pushes another own telegram too.
  void book_own() {
    if (own_unbooked_ != nullptr) book_own_now();
  }

  // Lazy hops (docs/serial-and-ring.md): when exactly one listener follows the line and the
  // burst is announced after everything before it (would_pass), the listener may take it and
  // hand it on (LineListener::pass_through); the line itself takes the burst later, by
  // absorb(), and until then nothing else here may read it (the repeater's absorb_passed()
  // comes first).
  // The lone follower's pass_through alone, nothing else set: inline when it is a plain
  // link (a ring's fibre), else by its call. What TxD hands on was checked where it came in
  // (bits, a bit period, not before now), so the link does not check it again.
  bool follower_takes(const LineBurst& burst, LineListener*& next, const LineBurst*& out) {
    return lone_link_ != nullptr ? lone_link_->pass_checked(burst, *this, next, out)
                                 : lone_follower_->pass_through(burst, next, out, *this);
  }
  // follower_takes() for a burst leaving at `leaves` that the caller keeps as it reaches
  // `next` (a lazy hop): `into` has its bits and bit period, and gets its start there.
  bool follower_takes_into(sim::Time leaves, LineBurst& into, LineListener*& next) {
    if (lone_link_ != nullptr) return lone_link_->pass_at(leaves, *this, next, into.start);
    return follower_takes_copy(leaves, into, next);
  }
  // The same naming `next`'s receiver (LineListener::receiver()): a lazy hop's.
  bool follower_takes_into(sim::Time leaves, LineBurst& into, LineListener*& next,
                           SerialReceiver*& receiver) {
    if (lone_link_ != nullptr)
      return lone_link_->pass_at(leaves, *this, next, into.start, receiver);
    if (!follower_takes_copy(leaves, into, next)) return false;
    receiver = next->receiver();
    return true;
  }
  // TxD's own conditions for passing a burst leaving at `leaves` to the lone follower.
  inline bool would_pass(sim::Time leaves) const;  // serial_unit_pass_through.hpp
  void set_follower_delay(sim::Time delay) { follower_delay_ = delay; }
  // `*to` is kept equal to the lone follower's plain link (null: none, or stop): the
  // receiver's lazy hops read it there, without a load of this object.
  void mirror_lone_link(PlainLink** to) {
    link_mirror_ = to;
    if (to != nullptr) *to = lone_link_;
  }
  // How long after leaving a burst the lone follower took reaches the listener behind it.
  sim::Time follower_delay() const { return follower_delay_; }
  // A burst passed through before: into the line as line_burst() would, no listener told
  // (the listener books it when it asks, book_all).
  inline void absorb(sim::Time start, sim::Time period, const SharedBits& bits);
  // absorb() of a burst that has reached the lone follower by now (so every burst before it
  // has too): the line is just it once pruned, set so at once. The repeater's settle().
  inline void settle(sim::Time start, sim::Time period, SharedBits&& bits);
  sim::Time last_since() const {
    return own_unbooked_ != nullptr ? own_unbooked_->start : line_.back().since;
  }
  // PassedBursts: the bursts the lone follower took by pass_through (lazy hops, and the
  // bursts line_burst() hands it) and has not booked, booked there in order. Every burst
  // leaving TxD reaches that listener this way when it takes it, so a plain fibre books
  // none of them unless something reads its history.
  void book_all() override;
  // line_burst() hands bursts to the lone follower unbooked (above): on unless lazy hops are
  // switched off, so that off is the full path at the fibre too (the tests compare both).
  void set_pass_unbooked(bool on) {
    book_own();
    if (!on && unbooked_ > 0) book_unbooked();
    pass_unbooked_ = on;
  }

  // Registers, test mode, polarity, clocks or reset state changed: re-derive every pin and
  // tell the listeners whose view changed.
  void refresh();

  // What the line is in now, for a listener that joins: mid-telegram counts as idle fill.
  LineCondition line_condition_now(sim::Time* period) const;

 private:
  void change_condition(sim::Time at, LineCondition condition, sim::Time period);
  void tell_left_dark(LineListener* left);  // a listener that left a pin (nullptr: none)
  enum class Mode : std::uint8_t { HighZ, Port, Dark, Light, ZeroBits, Line };
  struct View {  // what a listener is shown
    Mode mode = Mode::HighZ;
    LineCondition condition = LineCondition::Dark;  // for modes other than Line
    sim::Time period = 0;
    friend bool operator==(const View&, const View&) = default;
  };
  struct Output {
    LineListener* listener = nullptr;
    View view;
  };

  View view_of(unsigned pin) const;
  sim::Level pin_level(const View& view) const;
  void show(unsigned pin, const View& view);
  void set_pins_following_line();
  void tell_line(LineListener& listener) const;  // the line now, then what is announced
  bool supersede(sim::Time at);                  // true when something announced was dropped
  static bool is_dark(const RxdSegment& s) {     // no signal: the pins show the dark level
    return !s.is_burst && s.condition == LineCondition::Dark;
  }
  // The pins change only where the line goes dark or lights up; an announcement that does
  // neither (and drops nothing announced before) leaves the plan as it is. Inline: at every
  // burst.
  bool darkness_changes_at_back() const {
    if (line_.size() < 2) return true;
    return is_dark(line_.back()) != is_dark(line_[line_.size() - 2]);
  }
  // Drops the segments replaced by now. A burst the lone follower has not booked goes
  // unbooked when its successor has reached the far end too (the follower would drop it
  // at its next booking anyway); else the follower books first. Inline: at every burst.
  void prune() {
    const sim::Time now = scheduler_.now();
    while (line_.size() > 1 && line_[1].since <= now) {
      if (unbooked_ == line_.size()) {  // the front is one of them
        if (line_[1].since + follower_delay_ > now) {
          book_unbooked();
          continue;
        }
        --unbooked_;
      }
      pop_front_segment(line_);
    }
  }
  // drop_announced_from for the line: the bursts not booked are its last segments.
  bool drop_from(sim::Time at) {
    bool dropped = false;
    while (!line_.empty() && line_.back().since >= at) {
      line_.pop_back();
      if (unbooked_ > 0) --unbooked_;
      dropped = true;
    }
    return dropped;
  }
  // The last unbooked_ segments of the line into the lone follower (book_passed).
  [[gnu::noinline]] void book_unbooked();
  void book_own_now();
  void tell_followers(const LineBurst& burst);
  // follower_takes_into() through a listener without a plain link: by its pass_through.
  bool follower_takes_copy(sim::Time leaves, LineBurst& into, LineListener*& next);
  bool dark_now() const;
  const RxdSegment& line_now() const;
  void plan_pins();  // an event where the line next goes dark or lights up

  static void pass_on(LineListener& listener, const RxdSegment& segment);
  void find_lone_follower();  // after a listener or a view changed

  SerialUnit& unit_;
  sim::Scheduler& scheduler_;  // the chip's: asked for now at every burst
  std::array<Output, 6> outputs_{};
  LineListener* lone_follower_ = nullptr;  // the one listener following the line; none or two: null
  PlainLink* lone_link_ = nullptr;         // lone_follower_->plain_link()
  PlainLink** link_mirror_ = nullptr;      // kept equal to lone_link_ (mirror_lone_link)
  // The last unbooked_ segments of line_ are bursts the lone follower took by pass_through
  // and has not booked; they reach it follower_delay_ after they leave.
  std::size_t unbooked_ = 0;
  bool pass_unbooked_ = true;
  // An own telegram the lone follower took unbooked that the line has not taken yet
  // (own_burst): after line_'s last segment, and then the line's last segment. Points into
  // the repeater's queue of own telegrams, which keeps it until it pushes the next one
  // (book_own() before that).
  const LineBurst* own_unbooked_ = nullptr;
  sim::Time own_unbooked_end_ = 0;  // its end(), as the repeater worked it out
  sim::Time follower_delay_ = 0;
  // The serial line as announced, in time order, the front in force now: conditions, and
  // bursts (followed by Idle at their rate).
  sim::CircularQueue<RxdSegment> line_;
  sim::Scheduler::EventId pins_event_{};
};

}  // namespace sercon::chip

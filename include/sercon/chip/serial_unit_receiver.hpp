// The receiver on RxD (the LineListener behind SerialUnit::rxd()). It keeps what the line
// has announced (line.hpp) as a timeline: the segment in force now and those still to come.
// Each telegram burst is decoded when it is announced, once per shared bits object
// (line_decode_memo.hpp), and passed on to the repeater at once, so a telegram crosses a
// ring of repeaters without an event per hop. Events are spent only where something
// happens inside the chip:
// - reports to the telegram processor (address in, telegram detected), and only those its
//   present state makes it act on (ReceiveInterest): one pending event, the earliest;
// - the line monitor, only at changes into or out of a bad signal (dark, wrong rate);
// - RECACTN / RECACT are computed from the timeline when read (LazyPin, read hook).
// A burst at a bit period other than the receiver's is distorted: nothing is decoded (the
// line monitor raises RDIST). A change that comes before a burst's end cuts it there: the
// frame open at the cut ends as an error. docs/serial-and-ring.md, "Receiver".
// Its members are defined in four files: serial_unit_receiver.cpp (the timeline and the
// reports), serial_unit_lazy_hop.cpp (bursts coming in, lazy hops and their absorbing),
// serial_unit_receiver_inline.hpp (the inline steps those two share) and
// serial_unit_pass_through.hpp (the settle before an own telegram, inline in the
// transmitter's send, with the repeater's and TxD's parts of it).
#pragma once

#include <algorithm>
#include <array>
#include <cassert>
#include <cstdint>
#include <deque>
#include <memory>
#include <vector>

#include "sercon/chip/lazy_pin.hpp"
#include "sercon/chip/line.hpp"
#include "sercon/chip/line_decode_memo.hpp"
#include "sercon/chip/mclk_divider.hpp"
#include "sercon/chip/serial_unit.hpp"
#include "sercon/chip/serial_unit_input.hpp"
#include "sercon/chip/serial_unit_repeater.hpp"
#include "sercon/sim/circular_queue.hpp"
#include "sercon/sim/front_drop_vector.hpp"
#include "sercon/sim/reciprocal.hpp"
#include "sercon/sim/scheduler.hpp"
#include "sercon/sim/slot_queue.hpp"

namespace sercon::chip {

class SerialReceiver final : public LineListener, private LazyPin::Source {
 public:
  explicit SerialReceiver(SerialUnit& unit);
  ~SerialReceiver() override;
  SerialReceiver(const SerialReceiver&) = delete;
  SerialReceiver& operator=(const SerialReceiver&) = delete;

  // LineListener: a time before now is std::invalid_argument.
  void line_condition(sim::Time at, LineCondition condition, sim::Time bit_period) override;
  void line_burst(const LineBurst& burst) override;

  void reset();
  void release();
  // The bit rate changed: a telegram coming in at the old rate is cut now (the receiver is
  // clocked at the new one), telegrams still to come are judged (decoded or not) at the new.
  void refresh_rate();
  void on_start(SerialUnit::TelegramStartHandler handler);
  void on_telegram(SerialUnit::TelegramHandler handler);
  void on_start(void* context, SerialUnit::TelegramStartFn handler);
  void on_telegram(void* context, SerialUnit::TelegramFn handler);
  void set_interest(const ReceiveInterest* interest);
  void interest_changed() { plan_reports(); }

  // Lazy hops (docs/serial-and-ring.md, "Lazy hops"): a burst this chip does not look at
  // (no report wanted, RECACTN unwatched, between good signals, after everything announced
  // before) and that the repeater, TxD and the fibre behind would only pass on, goes
  // straight to the next receiver; this node keeps just the burst. absorb_lazy() takes such
  // bursts into the receiver, repeater and TxD timelines as the full path would have, and
  // runs before anything reads or changes them. Off: every burst takes the full path, at the
  // repeater, TxD and the fibre behind too (the
  // results are the same; the tests compare both).
  void set_lazy_hops(bool on);
  // After the unit's running state or bit period changes (SerialUnit) or REPON does (the
  // repeater), at once: the lazy hops' period, SCLK step and report lag, kept here.
  void refresh_hop_period();
  void absorb_lazy() {
    if (!lazy_.empty()) absorb_waiting();  // inline: asked before every change, mostly none
  }
  std::uint64_t lazy_hops_taken() const { return lazy_hops_taken_; }
  // absorb_lazy() for an own telegram (SerialRepeater::own), its usual case inline
  // (serial_unit_pass_through.hpp). True: the lazy burst settled (SerialRepeater::settle).
  [[gnu::always_inline]] inline bool absorb_lazy_for_own(sim::Time now);
  std::size_t lazy_bursts_waiting() const { return lazy_.size(); }  // not yet absorbed

  // What RxD carries now.
  const RxdSegment& input() const;
  // The received signal from now on, as the repeater takes it up (REPON switched on): the
  // segment in force now, then those announced for later.
  std::vector<RxdSegment> input_from_now() const;

 private:
  // A decoded frame's times: start and end worked out when it is decoded (or cut), the
  // report times when first asked for (most frames pass a chip that wants no report).
  // Set whole (FrameState{}: all zero and false) when a frame is taken: no member
  // initializers, so the states of an entry not yet taken cost nothing (FrameStates).
  struct FrameState {
    sim::Time start, end;       // opening flag at RxD; closing flag's end (or the cut)
    sim::Time start_report;     // address in + pipeline; kNever: no whole address
    sim::Time telegram_report;  // detection
    bool reports_known;         // start_report and telegram_report are worked out
    bool start_done, end_done;
    bool telegram_known;  // telegram_report is worked out (reports_known, or a frame read
                          // for its detection only: consider_one())
  };
  // Frame states without an allocation for the usual burst of one frame: in inline_ when
  // there is one, else all in more_ (contiguous either way, for the plans' walk). Small, as
  // the entry it is part of: the timeline moves its entries when the front one goes.
  // Only the first size() are ever read or copied: a new entry (every hop a node reads)
  // writes none of its inline states, where value-initialising them cleared the whole entry.
  class FrameStates {
   public:
    FrameStates() noexcept {}  // user-provided: an entry's value-initialisation leaves inline_
    FrameStates(const FrameStates& other) : size_(other.size_) {
      if (size_ <= kInline) {
        copy_inline(other);
      } else {
        more_ = std::make_unique<FrameState[]>(size_);
        std::copy_n(other.more_.get(), size_, more_.get());
      }
    }
    FrameStates(FrameStates&& other) noexcept : more_(std::move(other.more_)), size_(other.size_) {
      if (size_ <= kInline) copy_inline(other);
      other.size_ = 0;
    }
    FrameStates& operator=(const FrameStates& other) {
      if (this != &other) *this = FrameStates(other);
      return *this;
    }
    FrameStates& operator=(FrameStates&& other) noexcept {
      // The usual: states inline on both sides, or none (kInline == 1, copy_inline()).
      if (!more_ && !other.more_) {
        const std::uint32_t size = other.size_;
        other.size_ = 0;
        size_ = size;
        if (size > 0) inline_[0] = other.inline_[0];
        return *this;
      }
      if (this != &other) {
        more_ = std::move(other.more_);
        size_ = other.size_;
        if (size_ <= kInline) copy_inline(other);
        other.size_ = 0;
      }
      return *this;
    }
    ~FrameStates() = default;

    std::size_t size() const { return size_; }
    bool empty() const { return size_ == 0; }
    FrameState* data() { return size_ <= kInline ? inline_.data() : more_.get(); }
    const FrameState* data() const { return size_ <= kInline ? inline_.data() : more_.get(); }
    FrameState& operator[](std::size_t i) { return data()[i]; }
    const FrameState& operator[](std::size_t i) const { return data()[i]; }
    FrameState& back() { return data()[size_ - 1]; }
    // The state of an entry of one frame (size() == 1): inline, without data()'s choice.
    FrameState& only() {
      static_assert(kInline >= 1);
      assert(size_ == 1);
      return inline_[0];
    }
    const FrameState& back() const { return data()[size_ - 1]; }
    void clear() { resize(0); }
    // n new frame states (a burst taken afresh).
    void reset(std::size_t n) {
      if (n <= kInline) {
        for (std::size_t i = 0; i < n; ++i) inline_[i] = FrameState{};
      } else {
        more_ = std::make_unique<FrameState[]>(n);  // value-initialised
      }
      size_ = static_cast<std::uint32_t>(n);
    }
    // One frame state, `st` (reset(1) with it written in).
    void set_one(const FrameState& st) {
      inline_[0] = st;
      size_ = 1;
    }
    // The first min(size(), n) stay as they are; the others are new.
    void resize(std::size_t n) {
      if (n > kInline) {
        auto states = std::make_unique<FrameState[]>(n);  // value-initialised
        std::copy_n(data(), std::min<std::size_t>(size_, n), states.get());
        more_ = std::move(states);
      } else {
        if (size_ > kInline) {
          std::copy_n(more_.get(), n, inline_.begin());
        } else {
          for (std::size_t i = size_; i < n; ++i) inline_[i] = FrameState{};
        }
      }
      size_ = static_cast<std::uint32_t>(n);
    }

   private:
    static constexpr std::size_t kInline = 1;
    // The first size_ (<= kInline) states of `other`, copied as a whole: copy_n of a count
    // known only at run time was a memmove call at every entry the timeline moves.
    void copy_inline(const FrameStates& other) {
      static_assert(kInline == 1);
      if (size_ > 0) inline_[0] = other.inline_[0];
    }
    std::array<FrameState, kInline> inline_;  // the first size_ set (when size_ <= kInline)
    std::unique_ptr<FrameState[]> more_;      // all of them when size_ > kInline (else unused)
    std::uint32_t size_ = 0;
  };
  struct Entry {
    // User-provided: value-initialising the aggregate cleared all of it first.
    Entry(RxdSegment&& s, sim::Time c, std::uint64_t n)
        : segment(std::move(s)), cut(c), serial(n) {}
    // A burst's entry built in place (the usual read: no segment to move in).
    Entry(const LineBurst& b, std::uint64_t n)
        : segment{true, LineCondition::Idle, b.start, b.bit_period, b.bits},
          cut(b.end()),
          serial(n) {}
    RxdSegment segment;
    sim::Time cut = 0;  // bursts: where a later change cuts it (burst end when none)
    std::uint64_t serial = 0;
    const BurstDecode* decode = nullptr;  // of segment.bits; null: not taken (no burst, other
                                          // rate, reset, a lazy burst absorbed over)
    FrameStates frames;
  };
  struct Report {
    sim::Time when = 0;
    std::uint64_t serial = 0;  // of the entry
    std::size_t frame = 0;
    bool telegram = false;  // the detection; false: address in
  };

  using Handed = SerialRepeater::Handed;
  void announce(RxdSegment&& segment) { announce(segment.since, nullptr, &segment, nullptr); }
  // A burst read (line_burst's loop): its entry built in place. True: the repeater handed
  // it on unbooked, left in `handed` for the loop to deliver.
  bool announce(const LineBurst& burst, Handed& handed) {
    return announce(burst.start, &burst, nullptr, &handed);
  }
  // What changes at `at`: `burst`, else `segment` (moved into the timeline). With `handed`:
  // what goes on unbooked is left there (true) instead of delivered.
  bool announce(sim::Time at, const LineBurst* burst, RxdSegment* segment, Handed* handed);
  // Out of line, so announce() carries no message building.
  [[noreturn, gnu::cold, gnu::noinline]] static void refuse_past(sim::Time at, sim::Time now);
  [[noreturn, gnu::cold, gnu::noinline]] void refuse_more(sim::Time now) const;
  Entry& append(RxdSegment&& segment);
  // How a burst a hop try refused is read: by announce() (Full), or it has one frame whose
  // start report (ReadStart) or else detection (ReadTelegram) the processor wants, read by
  // read() with that known (the usual read at a slave).
  enum class HopTry : std::uint8_t { Full, ReadStart, ReadTelegram };
  // true: taken lazily; the caller delivers `out` to `next` (LineListener::pass_through).
  // false: read, as read_try_ says (the caller sets it back to Full).
  // Inline in line_burst(), as drop_lazy_over() in it: a call less per hop of a lazy chain.
  // `receiver`: next->receiver().
  inline bool try_lazy_hop(const LineBurst& burst, LineListener*& next, SerialReceiver*& receiver,
                           const LineBurst*& out);
  // announce(burst, handed) of a burst the hop try found `wanted` (ReadStart, ReadTelegram):
  // it comes after now at the unit's rate, with one frame, and the processor's answers for
  // it are known (twin tests: lazy hops on and off, which reads by announce()).
  // At a node whose repeater is off (a master) with lazy hops on, such a burst is read by
  // read() too, Full (consider_one() asks the answers), from announce_or_read(); it then
  // hands nothing on. Lazy hops off, it goes by announce() (the same twin tests).
  bool read(const LineBurst& burst, HopTry wanted, Handed& handed);
  // Out of line: line_burst()'s loop (its code matters at 254 slaves) calls it where it
  // called announce().
  [[gnu::noinline]] bool announce_or_read(const LineBurst& burst, Handed& handed);
  [[gnu::cold, gnu::noinline]] bool read_told(const Entry& e, bool changed, Handed& handed);
  [[gnu::cold, gnu::noinline]] static void hand_copy(LineListener& next, const LineBurst& out);
  // std::invalid_argument for a burst without bits or a bit period.
  void check(const LineBurst& burst) {
    if (!burst.bits || burst.bit_period <= 0) [[unlikely]]
      bad_burst(burst);
  }
  [[noreturn, gnu::cold]] static void bad_burst(const LineBurst& burst);
  template <bool kNote>
  bool wants_a_report(const LineBurst& burst);
  // What wants_a_report() and lazy_report_due() must look at, from the handlers and the
  // interest (set rarely, asked at every hop): no report at all; every report (one handler
  // only, or no interest); the frames, each asked of the interest.
  enum class HopCheck : std::uint8_t { None, Always, Frames };
  void refresh_hop_check() {
    if (!on_start_ && !on_telegram_) {
      hop_check_ = HopCheck::None;
    } else if (!on_start_ || !on_telegram_ || interest_ == nullptr) {
      hop_check_ = HopCheck::Always;
    } else {
      hop_check_ = HopCheck::Frames;
    }
    refresh_unrepeated_reads();
  }
  void refresh_unrepeated_reads() {
    unrepeated_reads_ =
        lazy_hops_ && unit_.running() && !unit_.repeater().on() && on_start_ && on_telegram_;
  }
  // Whether the processor may want a frame (the lazy checks): only those to address 255
  // are asked while it wants no other (ReceiveInterest::may_want_addressed).
  bool may_want(const wire::DecodedFrame& frame) const {
    return addressed_wanted_ || frame.address == kAddress255;
  }
  void refresh_interest() {
    if (wants_ != nullptr) {  // the usual case: an interest with data
      addressed_wanted_ = wants_->may_want_addressed();
    } else {
      addressed_wanted_ = interest_ == nullptr || interest_->may_want_addressed();
    }
  }
  // The processor's answers: from its published data when it has some, without a call
  // (the usual case, so the rest is out of line).
  bool wants_start(sim::Time start, std::uint8_t address) const {
    return wants_ != nullptr ? wants_->wants_start(start, address) : ask_start(start, address);
  }
  bool wants_telegram(sim::Time start, const wire::DecodedFrame& frame) const {
    return wants_ != nullptr ? wants_->wants_telegram(start, frame) : ask_telegram(start, frame);
  }
  // true without an interest
  [[gnu::noinline]] bool ask_start(sim::Time start, std::uint8_t address) const;
  [[gnu::noinline]] bool ask_telegram(sim::Time start, const wire::DecodedFrame& frame) const;
  void absorb_waiting();
  struct LazyBurst;
  // absorb_waiting()'s usual case and its entry, inline (serial_unit_pass_through.hpp): always,
  // as they are at every own telegram (absorb_lazy_for_own()).
  [[gnu::always_inline]] inline bool settle_lazy(sim::Time now);
  [[gnu::always_inline]] inline void take_in_front(const LazyBurst& lazy, bool over);
  inline void prune_lazy(sim::Time now);
  inline void drop_lazy_over(sim::Time now);
  // For the const readers of the timeline: the receiver itself is never const.
  void absorb_lazy_to_read() const { const_cast<SerialReceiver*>(this)->absorb_lazy(); }
  inline void pass_to_repeater(const Entry& e);
  // pass_to_repeater() leaving a burst that goes on unbooked in `handed` (true); chain_depth
  // stays counted up for it, and the caller's loop puts it back.
  inline bool pass_handing(const Entry& e, Handed& handed);
  [[gnu::cold, gnu::noinline]] void defer_forward(const Entry& e);  // the chain too deep
  void forward_deferred(std::uint64_t serial);
  bool supersede(sim::Time at);  // true when something announced before was changed
  void cut(Entry& entry, sim::Time at);
  // Decode if this chip receives it. `appended`: just appended, so not cut (cut is its end).
  void take(Entry& entry, bool appended = false);
  // take() of a burst at the receiver's rate whose decode `d` has one frame: what work_out()
  // makes of it.
  inline void take_one(Entry& entry, const BurstDecode& d);
  void prune();
  inline bool done_with(Entry& e, sim::Time now) const;    // prune()'s test of the front entry
  inline bool frames_over(Entry& e, sim::Time now) const;  // done_with() but for the report
  inline bool all_done_with(sim::Time now);                // done_with() every entry
  std::size_t in_force(sim::Time t) const;                 // index of the entry in force at t
  // The entry numbered `serial`, null when it is gone. Mostly the last one (a burst read
  // fires its reports before the next one comes): inline, the walk only for the others.
  Entry* find(std::uint64_t serial) {
    Entry& last = timeline_.back();
    return last.serial == serial ? &last : find_before_last(serial);
  }
  Entry* find_before_last(std::uint64_t serial);
  // The timeline holds more than `n` entries (n <= its size), asked by pointers: size()
  // divides by the entry's size, which is no power of two (asked several times a read).
  bool holds_more_than(std::ptrdiff_t n) const { return timeline_.begin() + n < timeline_.end(); }

  void work_out(Entry& e, std::size_t first);  // frame times from frame `first` on
  // Report times worked out (inline: asked at every plan, and mostly known by then).
  FrameState& with_reports(Entry& e, std::size_t frame) const {
    FrameState& st = e.frames[frame];
    if (!st.reports_known) work_out_reports(e, frame);
    return st;
  }
  // The detection's time, the start report's left as it is.
  sim::Time telegram_report(Entry& e, std::size_t frame) const {
    FrameState& st = e.frames[frame];
    if (!st.telegram_known) telegram_report_of(e, frame);
    return st.telegram_report;
  }
  void work_out_reports(Entry& e, std::size_t frame) const;
  [[gnu::always_inline]] inline void reports_of(
      Entry& e, std::size_t frame) const;  // what work_out_reports() does
  void telegram_report_of(Entry& e, std::size_t frame) const {
    FrameState& st = e.frames[frame];
    st.telegram_report = pipeline(st.end, e.segment.period);
    st.telegram_known = true;
  }
  // Both of the frame's reports are past at `now`, known without working them out.
  bool surely_over(const Entry& e, const FrameState& st, sim::Time now) const {
    return !st.reports_known && st.end + report_lag(e.segment.period) < now;
  }
  sim::Time pipeline(sim::Time t, sim::Time period) const;  // MCLK edge after t + 5.5 bit + 3
  void refresh_report_grid();                               // grid_, with hop_period_
  sim::Time report_lag(sim::Time period) const;             // bound on pipeline(t, period) - t
  void plan_reports();
  [[gnu::noinline]] void plan_by_walk(sim::Time now);  // plan_reports() but for its shortcut
  // No report of any entry can come at or after `now`.
  bool all_past(sim::Time now) const {
    for (const Entry& e : timeline_) {
      if (e.decode && !all_past(e, now)) return false;
    }
    return true;
  }
  // No report of e's frames can come at or after `now` (a start report without a whole
  // address never comes): the last frame's detection is past, and the reports of the
  // frames before it come before it. Worked out from the bound when not known yet.
  bool all_past(const Entry& e, sim::Time now) const {
    if (e.frames.empty()) return true;
    const FrameState& last = e.frames.back();
    return (last.telegram_known ? last.telegram_report : last.end + report_lag(e.segment.period)) <
           now;
  }
  bool lazy_report_due(sim::Time now);  // lazy_ not empty: a plan must absorb it first
  // Only `e` is new and nothing else changed: is one of its reports earlier than the one
  // planned?
  inline void consider(Entry& e);
  // One frame, nothing planned, both handlers. `known`: the processor's answers, when the
  // hop try has asked them (ReadStart, ReadTelegram); Full: asked here.
  inline void consider_one(Entry& e, HopTry known);
  [[gnu::noinline]] void consider_more(Entry& e);  // the others
  [[gnu::always_inline]] inline void arm(const Report& r);
  // The earliest report of e's frames the processor wants, if before best.when, into best.
  // fresh: e was just taken (none of its report times is known yet).
  void scan(Entry& e, sim::Time now, Report& best, bool fresh);
  bool candidate(Entry& e, FrameState& st, std::size_t frame, bool telegram, sim::Time now,
                 sim::Time before);
  template <bool kTelegram>  // the detection; false: the start report
  void fire_report();
  // fire_report() but for the usual report, out of line (flattened as fire_report() was):
  // the usual one then saves fewer registers and its lambda takes it inline.
  template <bool kTelegram>
  [[gnu::noinline, gnu::flatten]] void fire_found();
  // fire_start_of_only()'s end when the entry is no longer the last one's only frame.
  [[gnu::noinline, gnu::flatten]] void after_start(std::uint64_t serial);
  // fire_report() of the usual report, of `last`'s only frame (the last entry: a burst read
  // fires its reports before the next one comes), without find() or the frame's index.
  [[gnu::always_inline]] inline void fire_start_of_only(Entry& last);
  [[gnu::always_inline]] inline void fire_telegram_of_only(Entry& last);
  inline bool plan_telegram_after_start(const Report& fired);  // true: planned
  // A plan would find none (the last entry; else null); the entries before the fired one are
  // pruned on the way.
  inline Entry* nothing_after_detection(const Report& fired, sim::Time now);
  // The end of both detection paths: nothing_after_detection(), and then the last entry's
  // frames dropped once the burst can no longer be cut. False: the caller plans.
  [[gnu::always_inline]] inline bool done_after_detection(const Report& fired);
  inline bool start_report_past(const Entry& e, const FrameState& st, sim::Time now) const;
  void plan_monitor();
  void fire_monitor();
  inline bool good(const RxdSegment& s) const;  // edges at the receiver's rate

  // LazyPin::Source: RECACT (true = inside a telegram); the pin is its inverse.
  bool recact_at(sim::Time t) const;
  bool level_at(sim::Time t) const override { return !recact_at(t); }
  sim::Time next_change_after(sim::Time t) const override;

  SerialUnit& unit_;
  sim::Scheduler& scheduler_;  // the chip's, kept here: a hop asks for the time, one pointer less
  // The unit's TxD (made before the receiver, fixed for its life), kept here: from a node to
  // the next in a chain of lazy hops go as few loads one after the other as can be.
  TxdOutputs& txd_;
  PlainLink* hop_link_ = nullptr;  // txd_'s lone plain link (null: none), kept equal by txd_
  const MclkGrid& mclk_;           // the chip's, fixed for its life: the report times count in it
  // A report handler as it is called: a plain function and its context (a std::function
  // given is called through one of these, kept in start_function_ / telegram_function_).
  template <typename... Args>
  struct Handler {
    void (*call)(void* context, Args...) = nullptr;
    void* context = nullptr;
    explicit operator bool() const { return call != nullptr; }
    void operator()(Args... args) const { call(context, args...); }
  };
  Handler<sim::Time, std::uint8_t> on_start_;
  Handler<const ReceivedTelegram&> on_telegram_;
  SerialUnit::TelegramStartHandler start_function_;
  SerialUnit::TelegramHandler telegram_function_;
  void handlers_changed();
  const ReceiveInterest* interest_ = nullptr;
  const ReceiveWants* wants_ = nullptr;  // interest_->published(), read at every ask
  // interest_->may_want_addressed(), asked again at every plan and after every report.
  bool addressed_wanted_ = true;
  // Never empty; front in force now (or earlier). It holds a handful of entries, and the
  // front goes at most reads: a FrontDropVector drops it in place and moves the rest only
  // now and then (a std::vector moved them every time; a deque of entries this size would
  // allocate a block every second one). An Entry& does not outlive the next append.
  sim::FrontDropVector<Entry, 16> timeline_;
  std::uint64_t next_serial_ = 1;
  // Bursts passed on by lazy hops and not yet absorbed, in time order: as they reach the
  // next receiver (the burst the hop handed on, so it needs no copy of its own), and when
  // they reached RxD and left TxD. A slot of 64 bytes: every hop finds its slot by a shift
  // (at 56, by three instructions).
  struct alignas(64) LazyBurst {
    LineBurst reaching;  // the next receiver (the fibre books it only when it reads its history)
    sim::Time arrived = 0;
    sim::Time leaves = 0;
    sim::Time ends = 0;          // at RxD
    sim::Time reports_over = 0;  // after ends: what a report of its frames would come by
    sim::Time reaches() const { return reaching.start; }
  };
  // ~254 pass each node per cycle in Ring254, a few waiting at a time: slots reused, the
  // front and back as pointers (SlotQueue).
  sim::SlotQueue<LazyBurst, 32> lazy_;
  bool lazy_hops_ = true;
  // The rate a burst must come at to hop lazily: the unit's bit period while lazy hops are
  // on and the repeater too (0 while not running), else 0. Kept where those change (asked
  // at every hop).
  sim::Time hop_period_ = 0;
  sim::Time hop_lag_ = 0;  // report_lag(hop_period_): a lazy burst's reports_over
  // pipeline() at the unit's rate on an exact MCLK grid (the usual case), from values kept
  // with hop_period_ instead of MclkGrid's general path: for 0 <= t <= limit, the
  // kDetectionEdges-th MCLK edge after the first at or after t + 5.5 bits is
  // (floor((t + offset) / MCLK) + kDetectionEdges) * MCLK. When the MCLK period divides the
  // bit period (`shifts`), a time a whole number of bits later has its edge as many bits
  // later: a frame's start report comes that many bits before its detection (reports_of).
  struct ReportGrid {
    sim::Time period = 0;  // the bit period it holds for; 0: none
    sim::Time limit = 0;
    sim::Time offset = 0;  // 5.5 bits + an MCLK period - 1
    sim::Time mclk = 1;
    sim::Reciprocal by_mclk{1};
    bool shifts = false;
  };
  ReportGrid grid_;
  // The repeater's forward_time() for a hop, from these (set with hop_period_).
  sim::Time hop_due_ = 0;
  sim::Time hop_sclk_ = 1;
  sim::Reciprocal hop_by_sclk_{1};
  HopCheck hop_check_ = HopCheck::None;
  // Lazy hops on, running, the repeater off (a master), both handlers: announce_or_read()
  // may read(). Kept with hop_period_ and hop_check_.
  bool unrepeated_reads_ = false;
  HopTry read_try_ = HopTry::Full;  // noted by a hop try that ends in a read(); else Full
  std::uint64_t lazy_hops_taken_ = 0;
  std::uint64_t monitor_seen_ = 0;  // serial of the last entry the monitor has taken
  RxdSegment monitor_last_;         // that entry's segment (it may have been superseded since)
  Report report_{};                 // the planned report: read only while report_armed_
  // The entry whose report's handler runs: prune() keeps it (and so its bits, which the
  // frame handed to the handler lives in) until the handler returns.
  static constexpr std::uint64_t kNoSerial = UINT64_MAX;
  std::uint64_t firing_ = kNoSerial;
  struct Firing {
    Firing(SerialReceiver& r, std::uint64_t serial) : receiver(r) { r.firing_ = serial; }
    ~Firing() { receiver.firing_ = kNoSerial; }
    Firing(const Firing&) = delete;
    Firing& operator=(const Firing&) = delete;
    SerialReceiver& receiver;
  };
  // The report event: one owned scheduler slot per kind of report (fire_report<kind>), the
  // one of report_.telegram armed while report_armed_.
  sim::Scheduler::OwnedSlot start_report_event_;
  sim::Scheduler::OwnedSlot telegram_report_event_;
  bool report_armed_ = false;
  void cancel_report() {
    if (!report_armed_) return;
    scheduler_.cancel_owned(report_.telegram ? telegram_report_event_ : start_report_event_);
    report_armed_ = false;
  }
  sim::Scheduler::EventId monitor_event_{};
  // Forwards put off because the chain of announcements was too deep (a ring where every
  // node repeats: a telegram would circle it forever within one call).
  struct Deferred {
    std::uint64_t serial;
    sim::Scheduler::EventId event;
  };
  std::vector<Deferred> deferred_;
  LazyPin recactn_;
};

}  // namespace sercon::chip

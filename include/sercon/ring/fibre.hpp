// A fibre (or any point-to-point serial link): takes a transmitter's line at its input and
// delivers it to one receiver after a propagation delay. It schedules nothing: each
// announcement (line.hpp) is passed on at once with its time moved by the delay, so a
// telegram crosses a ring in one call chain. It can break and be restored at any time, and can flip
// line bits at random (seeded). docs/serial-and-ring.md, "Fibre".
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

#include "sercon/chip/line.hpp"
#include "sercon/chip/plain_link.hpp"
#include "sercon/ring/bit_errors.hpp"
#include "sercon/sim/circular_queue.hpp"
#include "sercon/sim/scheduler.hpp"

namespace sercon::ring {

class Fibre {
 public:
  // Light in glass or plastic fibre (refractive index about 1.5) travels 1 m in about 5 ns.
  static constexpr sim::Time kDefaultPsPerMetre = 5'000;

  // Delay = round(length_m * ps_per_metre) picoseconds. std::invalid_argument for a negative
  // or non-finite length or a per-metre delay below 0.
  explicit Fibre(sim::Scheduler& scheduler, double length_m = 0.0,
                 sim::Time ps_per_metre = kDefaultPsPerMetre);
  ~Fibre();
  Fibre(const Fibre&) = delete;
  Fibre& operator=(const Fibre&) = delete;

  // Where the transmitter (a chip's TxD, SerialUnit::connect_txd) delivers. The chip must
  // outlive the connection (or disconnect_txd first), as the receiver at the far end must:
  // bursts it passes on lazily are booked in this fibre's history from the chip when the
  // fibre asks (docs/serial-and-ring.md, "Lazy hops"). Ring and the C API free fibres first.
  chip::LineListener& input() { return input_; }
  // The receiver at the far end (a chip's rxd()); it is told the far end's present
  // condition at once. It must outlive the connection (or be disconnected first). The
  // receiver a fibre leaves (disconnect(), or connect() to another) is told Dark at now: its
  // signal is missing, as after a break.
  void connect(chip::LineListener& output);
  void disconnect();

  double length_m() const { return length_m_; }
  sim::Time delay() const { return link_.delay(); }

  // A break: the far end sees Dark from that moment (a telegram crossing it is cut there);
  // what enters meanwhile is lost. Restored, the far end gets what arrives then: the present
  // condition at once (a telegram half-way through counts as the idle fill after it).
  void break_now();
  void restore();
  void break_at(sim::Time t);    // std::invalid_argument if t is in the past
  void restore_at(sim::Time t);  // likewise
  bool broken() const { return broken_; }

  // Each line bit of each telegram is flipped with probability p (seeded; p = 0: off).
  void set_bit_error_rate(double p, std::uint64_t seed);
  std::uint64_t bit_errors() const { return errors_.flipped(); }

 private:
  class Input final : public chip::LineListener {
   public:
    explicit Input(Fibre& fibre) : LineListener(&fibre.link_), fibre_(fibre) {}
    void line_condition(sim::Time at, chip::LineCondition condition, sim::Time period) override;
    void line_burst(const chip::LineBurst& burst) override;
    bool pass_through(const chip::LineBurst& burst, chip::LineListener*& next,
                      const chip::LineBurst*& out, chip::PassedBursts& sender) override;
    void book_passed(const chip::LineBurst& burst) override;

   private:
    Fibre& fibre_;
  };

  // A change as the far end gets it (far-end time): a burst, or a condition at
  // burst.start with burst.bit_period as its period.
  struct Change {
    bool is_burst = false;
    chip::LineCondition condition = chip::LineCondition::Dark;
    chip::LineBurst burst;
  };
  void take(Change change);  // a condition from the input (its time still the input's)
  // std::invalid_argument for a time before now. Out of line and cold: a hop asks first.
  [[gnu::cold]] void check_not_past(sim::Time at) const;
  // A new last change of the history (the far end's time) at `start`, for the caller to
  // fill; the later word wins. Inline (fibre.cpp, its only callers).
  inline Change& record_at(sim::Time start);
  [[gnu::noinline]] void drop_from(sim::Time start);
  void pass_on(const Change& change);
  // The bursts passed through and not yet booked go into the history first (their sender
  // books them): before the history is read or added to.
  void book_passed() {
    if (chip::PassedBursts* const sender = link_.take_sender()) sender->book_all();
  }
  void tell_far_end();  // the far end's present condition, then what is still on its way
  // After a break, restore, connect, disconnect or bit error rate change.
  void update_plain() { link_.set(output_, !broken_ && !errors_.enabled()); }
  sim::Scheduler& scheduler_;
  double length_m_;
  sim::Time delay_;
  // Lazy hops: whole, without bit errors and connected, a burst passes through (asked at
  // every hop); the bursts passed through and not yet booked are held by their sender.
  // It keeps its own copies of delay_ and output_ (set with them), so that a sender's TxD
  // asks it inline without knowing the fibre.
  chip::PlainLink link_;
  Input input_{*this};
  chip::LineListener* output_ = nullptr;
  bool broken_ = false;
  BitErrors errors_;
  // What went in and reaches (or reached) the far end, in time order: the change in force
  // there now and those still on their way (kept while broken, for a restore).
  sim::CircularQueue<Change> history_;
  std::vector<sim::Scheduler::EventId> switches_;  // break_at / restore_at
};

}  // namespace sercon::ring

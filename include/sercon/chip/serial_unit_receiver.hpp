// The receiver on RxD: takes conditions and telegram bursts from a fibre or bus (it is the
// LineListener behind SerialUnit::rxd()), decodes each burst once per shared bits object
// (line_decode_memo.hpp), drives RECACTN, and reports the telegram processor's events at
// the simulated time they happen. A burst at a bit period other than the receiver's is
// distorted: nothing is decoded (the line monitor raises RDIST). A change that comes before
// a burst's end cuts it there: the frame open at the cut ends as an error.
// docs/serial-and-ring.md, "Receiver".
#pragma once

#include <deque>
#include <memory>
#include <vector>

#include "sercon/chip/line.hpp"
#include "sercon/chip/line_decode_memo.hpp"
#include "sercon/chip/serial_unit.hpp"
#include "sercon/chip/serial_unit_input.hpp"
#include "sercon/sim/scheduler.hpp"

namespace sercon::chip {

class SerialReceiver final : public LineListener {
 public:
  explicit SerialReceiver(SerialUnit& unit) : unit_(unit) {}
  ~SerialReceiver() override;
  SerialReceiver(const SerialReceiver&) = delete;
  SerialReceiver& operator=(const SerialReceiver&) = delete;

  // LineListener: `at` / burst.start must not lie before now nor before the last change;
  // changes announced for the future are taken when their time comes.
  void line_condition(sim::Time at, LineCondition condition, sim::Time bit_period) override;
  void line_burst(const LineBurst& burst) override;

  void reset();
  void release();
  void on_start(SerialUnit::TelegramStartHandler handler) { on_start_ = std::move(handler); }
  void on_telegram(SerialUnit::TelegramHandler handler) { on_telegram_ = std::move(handler); }

  const RxdSegment& input() const { return input_; }

 private:
  static constexpr std::size_t kNone = static_cast<std::size_t>(-1);
  // An event for the telegram processor waiting for its time. The scheduled callback holds
  // only `this` and the slot (no allocation per event).
  struct Report {
    std::shared_ptr<const BurstDecode> decode;  // keeps the frame alive
    std::size_t frame = 0;
    sim::Time start = 0, end = 0, detected = 0;
    bool telegram = false;  // the telegram event; false: the start event
    sim::Scheduler::EventId event;
  };
  struct FrameEvents {
    std::size_t address = kNone, detected = kNone;  // report slots
    sim::Scheduler::EventId address_event, detected_event;
    bool address_done = false;  // the start event ran (or the frame has no whole address)
  };
  struct Current {
    bool active = false;
    sim::Time start = 0, period = 0;
    sim::Time cut = 0;  // where a later change cut it; burst end when uncut
    SharedBits bits;
    std::shared_ptr<const BurstDecode> decode;
    std::vector<FrameEvents> events;
  };

  void check_order(sim::Time at);
  void take(const RxdSegment& segment);  // at now
  void cut_current(sim::Time at);
  void receive(const RxdSegment& burst);
  void schedule_frames(std::size_t first);
  void schedule_recact();  // RECACTN low from the first frame's start to the last one's end
  void set_recact(bool active);
  void retire_current();  // the current burst is over: its reports can no longer change
  sim::Time pipeline(sim::Time t) const;  // first MCLK edge at or after t + 5.5 bit + 3 MCLK
  std::size_t schedule_report(sim::Time when, Report report);
  void cancel_report(std::size_t slot, sim::Scheduler::EventId event);
  void fire(std::size_t slot);
  void cancel_chip_events();

  SerialUnit& unit_;
  SerialUnit::TelegramStartHandler on_start_;
  SerialUnit::TelegramHandler on_telegram_;
  RxdSegment input_;
  sim::Time last_change_ = 0;
  Current current_;
  std::vector<Report> reports_;  // slots; a free slot holds an empty Report
  std::vector<std::size_t> free_reports_;
  std::deque<sim::Scheduler::EventId> deferred_;  // changes announced for the future
  sim::Scheduler::EventId recact_event_{};
  bool recact_ = false;
};

}  // namespace sercon::chip

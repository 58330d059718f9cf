// An RS-485 bus (datasheet §1: "bus topologies with RS-485 signals are supported (Fig. 4)"):
// every node on one line, no repeaters. Decisions (docs/serial-and-ring.md, "RS-485 bus"):
// - A node drives the bus only while it sends a telegram (its driver enabled like IDLE): a
//   telegram its repeater passes on (REPON = 1) is not driven onto the bus;
//   between telegrams nobody drives and receivers see Dark (fail-safe level, no edges):
//   FIBBR on a bus means "bus silent". Conditions a node's TxD announces are not carried.
// - A telegram reaches every other node after the bus delay; a node does not hear itself.
// - Two telegrams that overlap collide: from the second one's start every receiver that hears
//   both gets one garbled burst, the wired OR of the levels, until the later end; the first
//   telegram is cut there (its receivers decode an Abort), the garbage fails the FCS or
//   aborts. A node that is itself sending hears only the others.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include "sercon/chip/line.hpp"
#include "sercon/chip/serial_unit.hpp"
#include "sercon/chip/serial_unit_transmitter.hpp"
#include "sercon/chip/settled_line.hpp"
#include "sercon/sim/scheduler.hpp"

namespace sercon::ring {

class Rs485Bus {
 public:
  // `delay` (>= 0) from any driver to any receiver.
  explicit Rs485Bus(sim::Scheduler& scheduler, sim::Time delay = 0);
  ~Rs485Bus();
  Rs485Bus(const Rs485Bus&) = delete;
  Rs485Bus& operator=(const Rs485Bus&) = delete;

  // A node: `receiver` hears the bus; driver(node) is where its transmitter delivers.
  // std::invalid_argument for a receiver that is a node already (it would hear itself).
  std::size_t add_node(chip::LineListener& receiver);
  chip::LineListener& driver(std::size_t node);
  // add_node(unit.rxd()) with the unit's TxD `txd_pin` driving the bus; a pin outside 1..6
  // (std::out_of_range) or a unit attached already is refused before anything changes.
  std::size_t attach(chip::SerialUnit& unit, unsigned txd_pin = 1);

  std::size_t node_count() const { return nodes_.size(); }
  std::uint64_t collisions() const { return collisions_; }
  sim::Time delay() const { return delay_; }

 private:
  struct Drive {
    std::size_t node;
    chip::LineBurst burst;
  };
  // A node's driver: what its transmitter announces (line.hpp) is checked, then waits in a
  // SettledLine until it happens; the bus arbitrates drivers at that moment ("now").
  class Driver final : public chip::LineListener {
   public:
    Driver(Rs485Bus& bus, std::size_t node) : now_(bus, node), settled_(bus.scheduler_, now_) {}
    // A chip's node: only bursts that start while `own` sends an own telegram are driven
    // (the driver is enabled like IDLE); a repeated telegram is not.
    void only_own(const chip::SerialTransmitter& own) { now_.own_ = &own; }
    // std::invalid_argument for a time before now or a burst without bits or bit period;
    // a later announcement supersedes what was announced for its time and later.
    void line_condition(sim::Time at, chip::LineCondition condition, sim::Time period) override;
    void line_burst(const chip::LineBurst& burst) override;

   private:
    // Takes each change at its time.
    class Now final : public chip::LineListener {
     public:
      Now(Rs485Bus& bus, std::size_t node) : bus_(bus), node_(node) {}
      void line_condition(sim::Time at, chip::LineCondition condition, sim::Time period) override;
      void line_burst(const chip::LineBurst& burst) override;

     private:
      Rs485Bus& bus_;
      std::size_t node_;
      const chip::SerialTransmitter* own_ = nullptr;  // nullptr: every burst is driven
      friend class Driver;
    };
    Now now_;
    chip::SettledLine settled_;
  };
  struct Node {
    chip::LineListener* receiver;
    std::unique_ptr<Driver> driver;
    bool silent;  // last told: Dark
  };

  void keep(sim::Scheduler::EventId id);
  void drive(std::size_t node, const chip::LineBurst& burst);  // at burst.start (bus time)
  void release(std::size_t node, sim::Time at);                // the node announced a condition
  void settle(sim::Time at);  // a burst ended: silence where nobody drives
  void drop_finished(sim::Time at);
  // Announces to a receiver, for `delay` later, a burst or (nullptr) silence.
  void tell(std::size_t receiver, sim::Time at, const chip::LineBurst* burst);
  std::vector<const Drive*> heard_by(std::size_t receiver) const;
  // The wired OR of `drives` from `at` to the latest end, sampled mid-bit at `period`.
  static chip::LineBurst garbled(const std::vector<const Drive*>& drives, sim::Time at,
                                 sim::Time period);

  sim::Scheduler& scheduler_;
  sim::Time delay_;
  std::vector<Node> nodes_;
  std::vector<Drive> active_;  // bursts on the bus now
  std::uint64_t collisions_ = 0;
  std::vector<sim::Scheduler::EventId> events_;
};

}  // namespace sercon::ring

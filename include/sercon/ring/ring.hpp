// A SERCOS ring (datasheet §1, Fig. 3; facts §2 "Ring"): one master and N slaves (1..254)
// on one scheduler, joined by fibres master TxD1 -> slave 1 RxD -> slave 1 TxD1 -> ... ->
// slave N TxD1 -> master RxD. docs/serial-and-ring.md, "Ring".
#pragma once

#include <cstddef>
#include <memory>
#include <vector>

#include "sercon/chip/chip.hpp"
#include "sercon/chip/chip_config.hpp"
#include "sercon/chip/serial_unit.hpp"
#include "sercon/ring/fibre.hpp"
#include "sercon/sim/scheduler.hpp"

namespace sercon::ring {

struct RingOptions {
  // One length per fibre, in ring order (fibre i leaves node i: 0 = master), N + 1 of
  // them; empty: every fibre is default_length_m long.
  std::vector<double> fibre_lengths_m;
  double default_length_m = 1.0;
  sim::Time ps_per_metre = Fibre::kDefaultPsPerMetre;
};

class Ring {
 public:
  static constexpr std::size_t kMaxSlaves = 254;  // facts §1: addresses 1..254

  // std::invalid_argument for 0 or more than 254 slaves, a wrong number of lengths, a bad
  // length, or a ChipConfig the chip refuses.
  Ring(sim::Scheduler& scheduler, const chip::ChipConfig& master,
       const std::vector<chip::ChipConfig>& slaves, const RingOptions& options = {});
  Ring(sim::Scheduler& scheduler, const chip::ChipConfig& master, const chip::ChipConfig& slave,
       std::size_t slave_count, const RingOptions& options = {});

  chip::Chip& master() { return *nodes_.front(); }
  chip::Chip& slave(std::size_t n);  // n = 1..slave_count(); std::out_of_range otherwise
  std::size_t slave_count() const { return nodes_.size() - 1; }
  chip::Chip& node(std::size_t i);  // 0 = master, i = slave i
  chip::SerialUnit& serial(std::size_t i);

  // Fibre i leaves node i's TxD1 and enters node i + 1's RxD (the last one the master's).
  Fibre& fibre(std::size_t i);
  std::size_t fibre_count() const { return fibres_.size(); }

  // What a driver does to bring its line up, for benches: every node's TxD1 driven with the
  // optical transmitter on (0x02 TXOE bit 0, TXLIGHT), repeaters on in the slaves and off in
  // the master (0x01 REPON), through register writes.
  void switch_on_lines();

 private:
  sim::Scheduler& scheduler_;
  std::vector<std::unique_ptr<chip::Chip>> nodes_;
  std::vector<chip::SerialUnit*> serials_;      // each node's, found once
  std::vector<std::unique_ptr<Fibre>> fibres_;  // destroyed first: they reference the nodes
};

}  // namespace sercon::ring

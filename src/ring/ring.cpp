#include "sercon/ring/ring.hpp"

#include <stdexcept>
#include <string>

#include "sercon/chip/register_map.hpp"

namespace sercon::ring {
namespace {

// The slave count of the one-config constructor, refused here so that the message names the
// count asked for (not the empty vector a larger count would have to become).
std::size_t checked_slave_count(std::size_t count) {
  if (count == 0 || count > Ring::kMaxSlaves) {
    throw std::invalid_argument("Ring: " + std::to_string(count) + " slaves; a ring has 1..254");
  }
  return count;
}

std::uint16_t mask_of(std::string_view field, chip::Variant variant) {
  const auto f = chip::find_field(field, variant);
  if (!f) throw std::logic_error("Ring: register field " + std::string(field) + " unknown");
  return f->mask();
}

}  // namespace

Ring::Ring(sim::Scheduler& scheduler, const chip::ChipConfig& master,
           const std::vector<chip::ChipConfig>& slaves, const RingOptions& options)
    : scheduler_(scheduler) {
  if (slaves.empty() || slaves.size() > kMaxSlaves) {
    throw std::invalid_argument("Ring: " + std::to_string(slaves.size()) +
                                " slaves; a ring has 1..254");
  }
  const std::size_t fibres = slaves.size() + 1;
  if (!options.fibre_lengths_m.empty() && options.fibre_lengths_m.size() != fibres) {
    throw std::invalid_argument("Ring: " + std::to_string(options.fibre_lengths_m.size()) +
                                " fibre lengths for " + std::to_string(fibres) + " fibres");
  }
  nodes_.reserve(fibres);
  nodes_.push_back(std::make_unique<chip::Chip>(scheduler_, master));
  for (const auto& config : slaves)
    nodes_.push_back(std::make_unique<chip::Chip>(scheduler_, config));
  for (const auto& n : nodes_) {
    auto* unit = n->unit<chip::SerialUnit>();
    if (!unit) throw std::logic_error("Ring: the chip has no serial unit");
    serials_.push_back(unit);
  }
  fibres_.reserve(fibres);
  for (std::size_t i = 0; i < fibres; ++i) {
    const double length =
        options.fibre_lengths_m.empty() ? options.default_length_m : options.fibre_lengths_m[i];
    fibres_.push_back(std::make_unique<Fibre>(scheduler_, length, options.ps_per_metre));
    serial(i).connect_txd(1, fibres_[i]->input());
    fibres_[i]->connect(serial((i + 1) % fibres).rxd());
  }
}

Ring::Ring(sim::Scheduler& scheduler, const chip::ChipConfig& master, const chip::ChipConfig& slave,
           std::size_t slave_count, const RingOptions& options)
    : Ring(scheduler, master,
           std::vector<chip::ChipConfig>(checked_slave_count(slave_count), slave), options) {}

chip::Chip& Ring::slave(std::size_t n) {
  if (n < 1 || n > slave_count()) {
    throw std::out_of_range("Ring: slave " + std::to_string(n) + " of " +
                            std::to_string(slave_count()));
  }
  return *nodes_[n];
}

chip::Chip& Ring::node(std::size_t i) {
  if (i >= nodes_.size()) {
    throw std::out_of_range("Ring: node " + std::to_string(i) + " of " +
                            std::to_string(nodes_.size()));
  }
  return *nodes_[i];
}

chip::SerialUnit& Ring::serial(std::size_t i) {
  node(i);  // range check
  return *serials_[i];
}

Fibre& Ring::fibre(std::size_t i) {
  if (i >= fibres_.size()) {
    throw std::out_of_range("Ring: fibre " + std::to_string(i) + " of " +
                            std::to_string(fibres_.size()));
  }
  return *fibres_[i];
}

void Ring::switch_on_lines() {
  for (std::size_t i = 0; i < nodes_.size(); ++i) {
    chip::Chip& c = *nodes_[i];
    const chip::Variant v = c.variant();
    const std::uint16_t txoe = mask_of("TXOE", v);
    const auto txoe1 = static_cast<std::uint16_t>(txoe & (~txoe + 1u));  // its lowest bit: TxD1
    const auto ctrl = static_cast<std::uint16_t>(c.reg_read(0x02) | mask_of("TXLIGHT", v) | txoe1);
    c.reg_write(0x02, ctrl);
    const std::uint16_t repon = mask_of("REPON", v);
    const std::uint16_t mode = c.reg_read(0x01);
    c.reg_write(0x01, static_cast<std::uint16_t>(i == 0 ? mode & ~repon : mode | repon));
  }
}

}  // namespace sercon::ring

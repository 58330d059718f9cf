#include "sercon/ring/rs485_bus.hpp"

#include <algorithm>
#include <map>
#include <stdexcept>
#include <string>

namespace sercon::ring {

using chip::LineBurst;
using chip::LineCondition;

namespace {

// Level of a burst at time x; false (nobody drives) outside it.
bool level_at(const LineBurst& b, sim::Time x) {
  if (x < b.start || x >= b.end()) return false;
  return b.bits->level(static_cast<std::size_t>((x - b.start) / b.bit_period));
}

}  // namespace

Rs485Bus::Rs485Bus(sim::Scheduler& scheduler, sim::Time delay)
    : scheduler_(scheduler), delay_(delay) {
  if (delay < 0)
    throw std::invalid_argument("Rs485Bus: delay " + std::to_string(delay) + " ps < 0");
}

Rs485Bus::~Rs485Bus() {
  for (const auto id : events_) scheduler_.cancel(id);
}

std::size_t Rs485Bus::add_node(chip::LineListener& receiver) {
  for (std::size_t i = 0; i < nodes_.size(); ++i) {
    if (nodes_[i].receiver == &receiver) {  // it would hear its own telegrams
      throw std::invalid_argument("Rs485Bus: the receiver is node " + std::to_string(i) +
                                  " already; a node does not hear itself");
    }
  }
  const std::size_t n = nodes_.size();
  nodes_.push_back(Node{&receiver, std::make_unique<Driver>(*this, n), true});
  receiver.line_condition(scheduler_.now(), LineCondition::Dark, 0);
  return n;
}

chip::LineListener& Rs485Bus::driver(std::size_t node) {
  if (node >= nodes_.size()) {
    throw std::out_of_range("Rs485Bus: node " + std::to_string(node) + " of " +
                            std::to_string(nodes_.size()));
  }
  return *nodes_[node].driver;
}

std::size_t Rs485Bus::attach(chip::SerialUnit& unit, unsigned txd_pin) {
  if (txd_pin < 1 || txd_pin > chip::SerialUnit::kTxdCount) {  // before the node is added
    throw std::out_of_range("TxD" + std::to_string(txd_pin) + ": the chip has TxD1..TxD6");
  }
  const std::size_t n = add_node(unit.rxd());
  nodes_[n].driver->only_own(unit.transmitter());
  unit.connect_txd(txd_pin, driver(n));
  return n;
}

void Rs485Bus::Driver::line_condition(sim::Time at, LineCondition condition, sim::Time period) {
  settled_.line_condition(at, condition, period);
}

void Rs485Bus::Driver::line_burst(const LineBurst& burst) {
  if (!burst.bits || burst.bit_period <= 0) {
    throw std::invalid_argument("Rs485Bus: a burst needs bits and a bit period > 0");
  }
  settled_.line_burst(burst);
}

void Rs485Bus::Driver::Now::line_condition(sim::Time at, LineCondition, sim::Time) {
  bus_.release(node_, at);
}

void Rs485Bus::Driver::Now::line_burst(const LineBurst& burst) {
  // The driver is enabled like IDLE: a burst that starts while the node's transmitter is not
  // sending (a repeated telegram) leaves the bus undriven by this node.
  if (own_ != nullptr && !own_->sending_at(burst.start)) return bus_.release(node_, burst.start);
  bus_.drive(node_, burst);
}

void Rs485Bus::keep(sim::Scheduler::EventId id) {
  if (events_.size() > 64) {
    std::erase_if(events_, [this](sim::Scheduler::EventId e) { return !scheduler_.pending(e); });
  }
  events_.push_back(id);
}

void Rs485Bus::tell(std::size_t receiver, sim::Time at, const LineBurst* burst) {
  Node& node = nodes_[receiver];
  if (!burst && node.silent) return;
  node.silent = !burst;
  chip::LineListener* listener = node.receiver;
  // An announcement (line.hpp): the receiver keeps it until `delay` has passed.
  const sim::Time far = at + delay_;
  if (burst) {
    LineBurst b = *burst;
    b.start = far;
    listener->line_burst(b);
  } else {
    listener->line_condition(far, LineCondition::Dark, 0);
  }
}

void Rs485Bus::drop_finished(sim::Time at) {
  std::erase_if(active_, [at](const Drive& d) { return d.burst.end() <= at; });
}

std::vector<const Rs485Bus::Drive*> Rs485Bus::heard_by(std::size_t receiver) const {
  std::vector<const Drive*> heard;
  for (const Drive& d : active_) {
    if (d.node != receiver) heard.push_back(&d);
  }
  return heard;
}

LineBurst Rs485Bus::garbled(const std::vector<const Drive*>& drives, sim::Time at,
                            sim::Time period) {
  sim::Time end = at;
  for (const Drive* d : drives) end = std::max(end, d->burst.end());
  const auto n = static_cast<std::size_t>((end - at + period - 1) / period);
  wire::LineBits bits;
  bits.reserve(n);
  for (std::size_t i = 0; i < n; ++i) {
    const sim::Time mid = at + static_cast<sim::Time>(i) * period + period / 2;
    bool high = false;
    for (const Drive* d : drives) high = high || level_at(d->burst, mid);
    bits.push_back(high);
  }
  return LineBurst{at, period, chip::share_bits(std::move(bits))};
}

void Rs485Bus::drive(std::size_t node, const LineBurst& burst) {
  const sim::Time at = burst.start;
  drop_finished(at);
  std::erase_if(active_, [node](const Drive& d) { return d.node == node; });  // cut its own
  const bool collision = !active_.empty();
  active_.push_back(Drive{node, burst});
  keep(scheduler_.at(burst.end(), [this, end = burst.end()] { settle(end); }));
  if (!collision) {
    for (std::size_t r = 0; r < nodes_.size(); ++r) {
      if (r != node) tell(r, at, &burst);
    }
    return;
  }
  ++collisions_;
  // Receivers hearing the same set of drivers share one garbled burst.
  std::map<std::vector<std::size_t>, LineBurst> made;
  for (std::size_t r = 0; r < nodes_.size(); ++r) {
    if (r == node) continue;  // its view (the others) does not change
    const auto heard = heard_by(r);
    if (heard.size() == 1) {
      tell(r, at, &burst);  // r was the only other driver: it hears the newcomer clean
      continue;
    }
    std::vector<std::size_t> key;
    for (const Drive* d : heard) key.push_back(d->node);
    auto it = made.find(key);
    if (it == made.end()) it = made.emplace(key, garbled(heard, at, burst.bit_period)).first;
    tell(r, at, &it->second);
  }
}

void Rs485Bus::release(std::size_t node, sim::Time at) {
  drop_finished(at);
  const auto own = std::find_if(active_.begin(), active_.end(),
                                [node](const Drive& d) { return d.node == node; });
  if (own == active_.end()) return;  // not driving: conditions are not carried
  const bool alone = active_.size() == 1;
  active_.erase(own);
  // A telegram cut short: its listeners see the bus fall silent. Under a collision the
  // garbage already sent stands (decision).
  if (alone) {
    for (std::size_t r = 0; r < nodes_.size(); ++r) {
      if (r != node) tell(r, at, nullptr);
    }
  }
}

void Rs485Bus::settle(sim::Time at) {
  drop_finished(at);
  for (std::size_t r = 0; r < nodes_.size(); ++r) {
    if (heard_by(r).empty()) tell(r, at, nullptr);
  }
}

}  // namespace sercon::ring

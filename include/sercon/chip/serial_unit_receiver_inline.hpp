// What the receiver's two source files share (serial_unit_receiver.cpp: the timeline and
// the reports; serial_unit_lazy_hop.cpp: bursts entering RxD and lazy hops): the chain
// guard and the report times, inline because they are asked at every hop.
#pragma once

#include <cstddef>

#include "sercon/chip/chip.hpp"
#include "sercon/chip/lazy_pin.hpp"
#include "sercon/chip/serial_unit_receiver.hpp"

namespace sercon::chip::receiver_detail {

constexpr sim::Time kNever = LazyPin::kNever;
// Longest chain of receivers one announcement may run through at once: more than a ring of
// 255 nodes needs, far less than the stack allows.
constexpr int kMaxChain = 600;
inline thread_local int chain_depth = 0;  // receivers in the chain now

}  // namespace sercon::chip::receiver_detail

namespace sercon::chip {

// The report times (worked out for every frame a node reads, and asked at every lazy hop
// and prune).
inline sim::Time SerialReceiver::report_lag(sim::Time period) const {
  return five_and_a_half_bits(period) + 4 * mclk_.period();
}

inline sim::Time SerialReceiver::pipeline(sim::Time t, sim::Time period) const {
  const sim::Time half_bits = five_and_a_half_bits(period);
  // kDetectionEdges MCLK edges after the first one at or after t + 5.5 bits (facts §5 t_start).
  return mclk_.nth_edge_after(t + half_bits, kDetectionEdges);
}

}  // namespace sercon::chip

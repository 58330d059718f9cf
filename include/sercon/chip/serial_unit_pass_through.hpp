// The repeater's and TxD's stages of a lazy hop (docs/serial-and-ring.md, "Lazy hops"),
// inline for the one caller, SerialReceiver::try_lazy_hop, and the repeater's forward time:
// asked at every hop of a lazy chain (~32 000 a cycle with 254 slaves), where a call per
// stage costs as much as its checks.
#pragma once

#include "sercon/chip/chip.hpp"
#include "sercon/chip/serial_unit.hpp"
#include "sercon/chip/serial_unit_outputs.hpp"
#include "sercon/chip/serial_unit_receiver.hpp"
#include "sercon/chip/serial_unit_repeater.hpp"

namespace sercon::chip {

inline sim::Time SerialRepeater::forward_time(sim::Time t) const {
  const sim::Time sclk = sclk_period_;
  const sim::Time due = t + SerialUnit::kRepeaterDelayBits * unit_.bit_period();
  if (due <= 0) return (due + sclk - 1) / sclk * sclk;  // before time 0: not on a ring
  return static_cast<sim::Time>(by_sclk_.divide(static_cast<std::uint64_t>(due + sclk - 1))) * sclk;
}

inline bool TxdOutputs::pass_through(const LineBurst& burst, LineListener*& next,
                                     const LineBurst*& out) {
  LineListener* only = lone_follower_;
  // Nothing announced at or after it to drop, and no change between dark and light (the
  // pins' plan stays as it is): what line_burst() would do is only to keep it.
  if (only == nullptr) return false;
  const RxdSegment& last = line_.back();
  if (last.since >= burst.start || (!last.is_burst && last.condition == LineCondition::Dark)) {
    return false;
  }
  return only->pass_through(burst, next, out, unit_.receiver());
}

inline bool SerialRepeater::pass_through(const LineBurst& leaving, LineListener*& next,
                                         const LineBurst*& out) {
  const sim::Time leaves = leaving.start;
  if (!repon_ || unit_.bit_period() == 0) return false;
  // What prune() would leave: no own telegram not yet over (they end in order), and the
  // background never pruned empty. Nothing is kept, so nothing needs pruning here.
  if (!own_.empty() && own_.back().end() > scheduler_.now()) return false;
  if (background_.empty() || background_.back().since >= leaves) return false;
  return unit_.outputs().pass_through(leaving, next, out);
}

}  // namespace sercon::chip

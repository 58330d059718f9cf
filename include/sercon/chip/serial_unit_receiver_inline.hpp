// What the receiver's two source files share (serial_unit_receiver.cpp: the timeline and
// the reports; serial_unit_lazy_hop.cpp: bursts entering RxD and lazy hops): the chain
// guard, the report times and the timeline's steps, inline because they are asked at every
// hop a node reads or absorbs.
#pragma once

#include <algorithm>
#include <cstddef>
#include <utility>

#include "sercon/chip/chip.hpp"
#include "sercon/chip/lazy_pin.hpp"
#include "sercon/chip/serial_unit_receiver.hpp"

namespace sercon::chip::receiver_detail {

constexpr sim::Time kNever = LazyPin::kNever;
// Longest chain of receivers one announcement may run through at once: more than a ring of
// 255 nodes needs, far less than the stack allows (the full path's hops nest calls; a lazy
// chain's turns of one loop count as hops too).
constexpr int kMaxChain = 600;
inline thread_local int chain_depth = 0;  // receivers in the chain now

// five_and_a_half_bits() of a burst's period (> 0), in unsigned arithmetic: the same value
// without the correction a signed division makes for negative numbers.
inline sim::Time burst_half_bits(sim::Time period) {
  return static_cast<sim::Time>((11 * static_cast<std::uint64_t>(period) + 1) / 2);
}

}  // namespace sercon::chip::receiver_detail

namespace sercon::chip {

// The report times (worked out for every frame a node reads, and asked at every lazy hop
// and prune).
inline sim::Time SerialReceiver::report_lag(sim::Time period) const {
  return five_and_a_half_bits(period) + 4 * mclk_.period();
}

inline sim::Time SerialReceiver::pipeline(sim::Time t, sim::Time period) const {
  // The usual: at the unit's rate on an exact grid (grid_), its edge by one multiply.
  if (period == grid_.period &&
      static_cast<std::uint64_t>(t) <= static_cast<std::uint64_t>(grid_.limit)) {
    const std::uint64_t first = grid_.by_mclk.divide(static_cast<std::uint64_t>(t + grid_.offset));
    return static_cast<sim::Time>((first + static_cast<std::uint64_t>(kDetectionEdges)) *
                                  static_cast<std::uint64_t>(grid_.mclk));
  }
  const sim::Time half_bits = receiver_detail::burst_half_bits(period);
  // kDetectionEdges MCLK edges after the first one at or after t + 5.5 bits (facts §5 t_start).
  return mclk_.nth_edge_after(t + half_bits, kDetectionEdges);
}

// Edges at the receiver's rate (a good signal). Inline: asked at a node's first lazy hop.
inline bool SerialReceiver::good(const RxdSegment& s) const {
  return s.has_edges() && s.period == unit_.bit_period();
}

// A new last entry (the caller has dropped what it supersedes), not yet taken.
inline SerialReceiver::Entry& SerialReceiver::append(RxdSegment&& segment) {
  const sim::Time cut = segment.is_burst ? segment.burst_end() : segment.since;
  return timeline_.emplace_back(std::move(segment), cut, next_serial_++);
}

inline void SerialReceiver::take(Entry& e, bool appended) {
  e.decode = nullptr;
  const RxdSegment& s = e.segment;
  if (!s.is_burst || s.period != unit_.bit_period()) {  // distorted: the monitor counts it
    e.frames.clear();
    return;
  }
  const BurstDecode& d =
      appended || s.burst_end() == e.cut
          ? decode_burst(s.bits)
          : decode_burst_prefix(s.bits, static_cast<std::size_t>((e.cut - s.since) / s.period));
  if (d.frames.size() == 1) return take_one(e, d);  // the usual burst, one telegram
  e.decode = &d;
  e.frames.reset(d.frames.size());
  work_out(e, 0);
}

inline void SerialReceiver::take_one(Entry& e, const BurstDecode& d) {
  const RxdSegment& s = e.segment;
  e.decode = &d;
  const wire::DecodedFrame& f = d.frames[0];
  e.frames.set_one(
      FrameState{s.since + static_cast<sim::Time>(f.start_bit) * s.period,
                 std::min(s.since + static_cast<sim::Time>(f.end_bit) * s.period, e.cut), 0, 0,
                 false, false, false, false});
}

inline void SerialReceiver::work_out(Entry& e, std::size_t first) {
  const BurstDecode& d = *e.decode;
  const sim::Time since = e.segment.since, period = e.segment.period;
  for (std::size_t i = first; i < e.frames.size(); ++i) {
    const wire::DecodedFrame& f = d.frames[i];
    FrameState& st = e.frames[i];
    st.start = since + static_cast<sim::Time>(f.start_bit) * period;
    st.end = std::min(since + static_cast<sim::Time>(f.end_bit) * period, e.cut);
    st.reports_known = st.telegram_known = false;
  }
}

// No report of e's is to come, nor is one planned or being fired: once a later entry is in
// force, e can go.
inline bool SerialReceiver::done_with(Entry& e, sim::Time now) const {
  if ((e.serial == report_.serial && report_armed_) || e.serial == firing_) return false;
  return frames_over(e, now);
}

// No report of e's frames is still to come. Mostly none is left (a burst not taken, or one
// whose detection has fired): known at once.
inline bool SerialReceiver::frames_over(Entry& e, sim::Time now) const {
  if (e.frames.empty()) return true;
  // The last frame's detection (after its end) still to come? It comes at most 5.5 bits
  // + 4 MCLK periods after the end (pipeline()): past that it need not be worked out.
  const FrameState& last = e.frames.back();
  if (last.end >= now) return false;
  return surely_over(e, last, now) || telegram_report(e, e.frames.size() - 1) < now;
}

inline bool SerialReceiver::all_done_with(sim::Time now) {
  // Nothing planned or being fired (the usual case at an own telegram's settle): only the
  // frames are left to ask.
  if (!report_armed_ && firing_ == kNoSerial) {
    for (Entry& e : timeline_) {
      if (!frames_over(e, now)) return false;
    }
    return true;
  }
  for (Entry& e : timeline_) {
    if (!done_with(e, now)) return false;
  }
  return true;
}

// Entries over and done with: a later one is in force and no report of theirs is to come.
inline void SerialReceiver::prune() {
  const sim::Time now = scheduler_.now();
  while (holds_more_than(1) && timeline_[1].segment.since <= now) {
    Entry& e = timeline_.front();
    if (!done_with(e, now)) return;
    timeline_.pop_front();  // the others stay where they are
  }
}

}  // namespace sercon::chip

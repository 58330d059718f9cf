// What the receiver's RxD carries from one change to the next: a condition, or a telegram
// burst followed by idle fill at the burst's rate (line contract: the line returns to Idle
// at burst.end() unless another change comes). The line monitor counts its edges.
#pragma once

#include <cstdint>
#include <string_view>
#include <utility>

#include "sercon/chip/line.hpp"
#include "sercon/chip/line_decode_memo.hpp"
#include "sercon/sim/time.hpp"
#include "sercon/sim/vector_queue.hpp"

namespace sercon::chip {

struct RxdSegment {
  bool is_burst = false;
  LineCondition condition = LineCondition::Dark;  // when !is_burst
  sim::Time since = 0;                            // the condition's or the burst's start
  sim::Time period = 0;                           // bit period; 0 for Dark and Light
  SharedBits bits;                                // when is_burst

  static RxdSegment of(sim::Time at, LineCondition condition, sim::Time period) {
    return RxdSegment{false, condition, at, period, nullptr};
  }
  static RxdSegment of(const LineBurst& burst) {
    return RxdSegment{true, LineCondition::Idle, burst.start, burst.bit_period, burst.bits};
  }

  LineBurst burst() const { return LineBurst{since, period, bits}; }
  sim::Time burst_end() const {  // since + bits * period (bursts only)
    return since + static_cast<sim::Time>(bits ? bits->size() : 0) * period;
  }
  bool has_edges() const {
    return is_burst || condition == LineCondition::Idle || condition == LineCondition::ZeroBits;
  }
  // The condition a repeater passes on when it joins at `t`: a burst counts as the idle
  // fill it is followed by (a fragment without its opening flag decodes to nothing).
  LineCondition condition_at_join() const { return is_burst ? LineCondition::Idle : condition; }
};

// A line's announced segments in time order, the front in force now (repeater, TxD):
// drops those announced for `at` or later (the later word wins, line.hpp); true if any.
// Inline: at every hop, and usually nothing to drop.
template <class Line>
inline bool drop_announced_from(Line& line, sim::Time at) {
  bool dropped = false;
  while (!line.empty() && line.back().since >= at) {
    line.pop_back();
    dropped = true;
  }
  return dropped;
}
// pop_front() for a line whose every push sets the whole segment (a repeater's, TxD's): the
// bits are let go now, the rest of the slot is left for the push that reuses it.
template <class Line>
inline void pop_front_segment(Line& line) {
  line.front().bits = nullptr;
  line.drop_front();
}
// Drops the segments a later one has replaced by `now`; the one in force stays.
template <class Line>
inline void drop_replaced_by(Line& line, sim::Time now) {
  while (line.size() > 1 && line[1].since <= now) pop_front_segment(line);
}

// `s` written over with the burst from `since` (what RxdSegment::of() makes of it, in place:
// the slot's storage kept): a line's new or settled segment, a receiver's settled entry.
template <class Bits>
inline void write_burst(RxdSegment& s, sim::Time since, sim::Time period, Bits&& bits) {
  s.is_burst = true;
  s.condition = LineCondition::Idle;
  s.since = since;
  s.period = period;
  s.bits = std::forward<Bits>(bits);
}

// Appends `burst` to a line (repeater, TxD) as a segment from `since`, built in its slot
// rather than copied in: at every hop. What it needs of the burst is taken first (the bits
// by value): the burst may live in storage the append moves (a fibre's history, say).
template <class Line>
inline void append_burst(Line& line, sim::Time since, sim::Time period, SharedBits bits) {
  write_burst(line.emplace_back(), since, period, std::move(bits));
}
template <class Line>
inline void append_burst(Line& line, const LineBurst& burst, sim::Time since) {
  append_burst(line, since, burst.bit_period, burst.bits);
}

// Lazy hops (docs/serial-and-ring.md): a lazy burst is booked into `line` (a name for the
// message) after the change announced last there, at `last`; every other way into the line
// takes lazy bursts in first, so one at or before `last` is a missed trigger:
// std::logic_error.
[[noreturn, gnu::cold]] void absorbed_out_of_order(std::string_view line, sim::Time last,
                                                   sim::Time at);
inline void expect_absorbed_in_order(std::string_view line, sim::Time last, sim::Time at) {
  if (last >= at) [[unlikely]]
    absorbed_out_of_order(line, last, at);
}

// Edges in [since, t): Idle has one every 8 bit times, ZeroBits one every bit time, both
// beginning with an edge at `since`; a burst has its bits' edges, then its trailing fill.
std::uint64_t edges_before(const RxdSegment& segment, sim::Time t);

// Time of the n-th (n >= 1) edge; the segment must have edges.
sim::Time nth_edge_time(const RxdSegment& segment, std::uint64_t n);

}  // namespace sercon::chip

// The receiver's rules, one decoded bit at a time (sercos-facts §1): a 0 after five 1s is
// a stuffed 0, a 0 after six 1s ends a flag, a seventh 1 is an abort (or idle fill). The
// decoder's tables (8-bit windows, and the last 1..7 bits of a feed) are generated from
// these functions, so the rules exist once.
#pragma once

#include <cstdint>

namespace sercon::wire::detail {

inline constexpr unsigned kSaturated = 7;  // run of 1s: seven or more (idle, abort, start)

enum class Action : std::uint8_t { None, Emit0, Emit1, Flag, Abort };

struct RxState {
  unsigned run = kSaturated;  // consecutive 1s so far
  bool zero_emitted = false;  // the 0 before the run went into the frame as data
};

// No frame open: only flags matter.
constexpr Action hunt_step(RxState& s, unsigned bit) {
  if (bit != 0) {
    if (s.run < kSaturated) ++s.run;
    return Action::None;
  }
  const bool flag = s.run == 6;
  s.run = 0;
  s.zero_emitted = false;
  return flag ? Action::Flag : Action::None;
}

// Inside a frame (run is 0..6 here: the seventh 1 ends the frame).
constexpr Action frame_step(RxState& s, unsigned bit) {
  if (bit != 0) {
    ++s.run;
    if (s.run <= 5) return Action::Emit1;
    return s.run == 6 ? Action::None : Action::Abort;  // the sixth 1 waits for the next bit
  }
  Action a = Action::Emit0;
  if (s.run == 5) {
    a = Action::None;  // stuffed 0: dropped
    s.zero_emitted = false;
  } else if (s.run == 6) {
    a = Action::Flag;  // zero_emitted still describes the 0 before the six 1s
  } else {
    s.zero_emitted = true;
  }
  s.run = 0;
  return a;
}

}  // namespace sercon::wire::detail

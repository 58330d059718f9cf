// What travels on a serial line (a fibre, or the RS-485 wire) between a transmitter and
// the receivers behind it, scheduled per telegram, not per bit (architecture guide):
// a line is in one condition at a time, and telegrams are bursts of exact line bits with
// an exact start time. The chip's serial unit emits these on its TxD side and takes them
// on its RxD side; fibres and buses (ring layer) carry them, with delay, breaks and bit
// errors. Nothing here knows about registers or telegram lists.
#pragma once

#include <cstdint>
#include <memory>
#include <string_view>

#include "sercon/chip/shared_bits.hpp"
#include "sercon/sim/time.hpp"

namespace sercon::chip {

// The state of a line between and around telegrams.
enum class LineCondition : std::uint8_t {
  Dark,      // no light / undriven: no edges (transmitter off, high-Z, fibre broken)
  Idle,      // idle fill: a level change every 8 bit times (sercos-facts §1)
  Light,     // continuous light (test mode, delta spec 2.3.3): no edges
  ZeroBits,  // zero bit stream (test mode): a level change every bit time
};

constexpr std::string_view to_string(LineCondition c) {
  switch (c) {
    case LineCondition::Dark:
      return "dark";
    case LineCondition::Idle:
      return "idle";
    case LineCondition::Light:
      return "light";
    case LineCondition::ZeroBits:
      return "zero-bits";
  }
  return "?";
}

// One telegram on the line: the opening flag to the closing flag, NRZI levels as sent.
// The bits are shared (not copied) by every hop that passes them on unchanged; a hop that
// changes them (a bit error) makes its own copy.
struct LineBurst {
  sim::Time start = 0;       // leading edge of the first line bit, at this point of the line
  sim::Time bit_period = 0;  // ps per bit (62'500 at 16 Mbit/s)
  SharedBits bits;

  sim::Time duration() const {
    return bits ? static_cast<sim::Time>(bits->size()) * bit_period : 0;
  }
  sim::Time end() const { return start + duration(); }
};

// A sender that hands bursts on by pass_through (below; a chip's TxD): it keeps the bursts a
// listener took without booking them, and books them there (LineListener::book_passed, in order)
// when the listener asks (book_all), before the listener reads or changes what it holds.
class PassedBursts {
 public:
  virtual void book_all() = 0;

 protected:
  ~PassedBursts() = default;
};

// Something that listens to a line (a chip's receiver, a fibre's input, a tracer).
//
// Announcements: a sender tells what it will put on the line as soon as it knows it, so a
// call's time (`at`, `burst.start`) is never before the scheduler's now but may lie in the
// future (a fibre passes a telegram on at once, its start moved by the delay; a repeater
// announces where a telegram will leave it). This is what lets a telegram cross a ring of
// repeaters without an event per hop. The later word wins: a call supersedes everything
// announced before for its time and later, and cuts a telegram under way at its time. So
// a listener keeps what was announced until its time comes, and drops what a later call
// overtakes. A listener that wants each change at the moment it happens, in time order,
// sits behind a SettledLine (settled_line.hpp).
class PlainLink;
class SerialReceiver;

class LineListener {
 public:
  virtual ~LineListener() = default;
  // The line enters `condition` at time `at` >= now (bit_period says how fast idle/zero-bit
  // edges come; 0 for Dark/Light).
  virtual void line_condition(sim::Time at, LineCondition condition, sim::Time bit_period) = 0;
  // A telegram begins on the line at burst.start >= now; the line returns to Idle at
  // burst.end() unless another change is announced before that.
  virtual void line_burst(const LineBurst& burst) = 0;

  // Lazy hops (docs/serial-and-ring.md, "Lazy hops"): a listener that passes a burst on
  // unchanged to exactly one other listener (a whole fibre without bit errors) may take it
  // as line_burst() would and, instead of telling that one, hand it back: `next` and the
  // burst as it reaches `next`, for the caller to deliver at once (`out` points into the
  // listener, valid until it is told anything else: no copy of the bits per hop; it has the
  // burst's own bits and bit period, only its start later, so `next` need not check them
  // again and a sender may keep its own copy instead). False
  // (the default): nothing was taken, call line_burst(). Taken, the burst need not be
  // booked yet: `sender` keeps it and books it by book_passed() when the listener asks
  // (PassedBursts::book_all), or before it tells the listener anything else.
  virtual bool pass_through(const LineBurst& burst, LineListener*& next, const LineBurst*& out,
                            PassedBursts& sender) {
    (void)burst, (void)next, (void)out, (void)sender;
    return false;
  }
  // A burst taken by pass_through before (its start as it was passed in), booked now as
  // line_burst() would have booked it then, telling no one.
  virtual void book_passed(const LineBurst& burst) { (void)burst; }

  // A chip's receiver, set only by the receiver itself (null for every other listener, a
  // wrapper around a receiver too): a chain of lazy hops goes on from receiver to receiver
  // in one loop, calling the next receiver's checks in place of its line_burst()
  // (SerialReceiver::line_burst), so what it names must be the listener itself.
  SerialReceiver* receiver() const { return receiver_; }
  // A plain link's input (null for every other listener): its pass_through is data a
  // sender asks inline (plain_link.hpp).
  PlainLink* plain_link() const { return plain_link_; }

 protected:
  LineListener() = default;
  explicit LineListener(SerialReceiver* receiver) : receiver_(receiver) {}
  explicit LineListener(PlainLink* link) : plain_link_(link) {}

 private:
  SerialReceiver* receiver_ = nullptr;
  PlainLink* plain_link_ = nullptr;
};

}  // namespace sercon::chip

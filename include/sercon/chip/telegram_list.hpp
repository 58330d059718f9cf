// The list walk of one cycle (docs/telegram-processing.md, "The list walk"): from COMPT0 /
// COMPT1 along the PT pointers, one item at a time as the hardware does (the next header
// is read when the present item starts), each item waiting for its time on the cycle
// counter:
//  - transmit header: due at the step out of TRT; the client sends (or not), the walk
//    goes on at once;
//  - receive header: waits for its telegram. TCHK = 1: the opening flag must start in the
//    window TRT - kWindowUs .. TRT + kWindowUs µs; the header is missed when no telegram
//    began in it, judged once a telegram that began at its end would have been reported
//    (ListClient::start_report_delay). TCHK = 0: any time until the cycle ends. ACHK = 1:
//    only its address;
//  - end marker: INT_ENDMK at the step out of TEND; the walk is over.
// An item whose time has already passed when it is read is late: a transmit telegram is
// not sent, a receive header is missed, an end marker ends the list at once. A fault (a
// pointer or container beyond the RAM, kind 10, more items than the RAM can hold) stops
// the walk until the next cycle.
#pragma once

#include <cstdint>
#include <limits>

#include "sercon/chip/serial_unit.hpp"
#include "sercon/chip/telegram_header.hpp"
#include "sercon/chip/telegram_ram.hpp"
#include "sercon/chip/time_base.hpp"

namespace sercon::chip {

struct ListItem {
  telegram::Kind kind = telegram::Kind::EndMarker;
  std::uint16_t address = 0;  // RAM word of word 0
  std::uint16_t word0 = 0;
  std::uint16_t time = 0;    // TRT or TEND (µs after the end of the MST)
  std::uint16_t length = 0;  // TLEN, data words
  std::uint16_t next = 0;    // PT

  std::uint8_t adr() const { return static_cast<std::uint8_t>(word0 & telegram::kAdrMask); }
  bool has(std::uint16_t bit) const { return (word0 & bit) != 0; }
};

// What the walk asks of the telegram processor.
class ListClient {
 public:
  virtual ~ListClient() = default;
  virtual void transmit_due(const ListItem& item) = 0;
  virtual void receive_missed(const ListItem& item) = 0;
  virtual void end_reached(const ListItem& item) = 0;
  virtual void list_fault(const ListFault& fault) = 0;
  // Longest time from a telegram's opening flag to its start report (address in).
  virtual sim::Time start_report_delay() const = 0;
  // The walk moved on by itself (an item's time came, a window closed) and what offer()
  // would answer may have changed: a receive header waited before or waits now.
  virtual void list_moved() = 0;
  // end_reached() would change nothing now (INT_ENDMK latched): the end marker's event is
  // then held out of the scheduler's queue until end_may_change() is called on the list.
  virtual bool end_changes_nothing() const { return false; }
};

// The walk's names that do not depend on its client.
struct TelegramListTypes {
  // Half-width of the TCHK window in µs (project decision).
  static constexpr std::int64_t kWindowUs = 2;

  enum class Match : std::uint8_t {
    NotExpected,   // no receive header waits, or the telegram is outside its window
    OtherAddress,  // in the window of an ACHK = 1 header, but another address
    Accepted,
  };
};

// `Client` is a ListClient: the list calls it as that type, so a client class that is final
// (the telegram processor) has its handlers called directly and inlined into the walk's
// events, one function per event; TelegramList calls any ListClient through its virtual
// functions. The member functions are in telegram_list_walk.hpp (TelegramList's compiled
// once, in telegram_list.cpp).
template <class Client>
class BasicTelegramList : public TelegramListTypes {
 public:
  BasicTelegramList(TimeBase& time_base, TelegramRam& ram, Client& client);
  ~BasicTelegramList();
  BasicTelegramList(const BasicTelegramList&) = delete;
  BasicTelegramList& operator=(const BasicTelegramList&) = delete;

  // A cycle starts: a receive header still waiting is missed, then the walk starts at
  // the list RAM word `list_pointer` names (COMPT0 or COMPT1). The walk's functions are
  // flattened (declared so: GCC takes a template member's attributes from its declaration).
  [[gnu::flatten]] void start(std::uint16_t list_pointer);
  // Forgets the walk (reset); no client calls.
  void stop();

  // A telegram whose opening flag began at `start` brings `address`: is it the waiting
  // receive header's? Accepted: `item` is that header, and the walk has moved on, except
  // for address 255: that may be an MST (no list telegram), so the walk stays at the header
  // until the detection says (taken() or reclaim()).
  // Inline: the receiver's start report of every telegram a header waits for comes here.
  Match offer(sim::Time start, std::uint8_t address, ListItem& item) {
    const Match match = would_take(start, address);
    if (match != Match::Accepted) return match;
    item = item_;
    // A receive header waits: event_ (transmit, end marker) is not armed, only a TCHK
    // window's judgement may be.
    cancel_window_judge();
    // Doc §2: the walk reaches the items behind a receive header only once it is served; an
    // address-255 telegram may still prove to be an MST, which serves no header (§3).
    if (address == kAddress255) {
      set_state(State::Held);
      return Match::Accepted;
    }
    walk_past(item);
    return Match::Accepted;
  }
  // An accepted address-255 telegram proved to be a list telegram at its detection: the walk
  // moves on past `item`. Nothing if the walk is no longer held there (a new cycle, a fault).
  // Inline: only an address-255 telegram holds the walk, most telegrams leave at once.
  void taken(const ListItem& item) {
    if (state_ == State::Held && item_.address == item.address) walk_past(item);
  }
  // What offer() would answer now, without taking the telegram. Inline: the receiver asks
  // at every telegram start.
  Match would_take(sim::Time start, std::uint8_t address) const {
    if (!wait_.waits || !wait_.in_window(start)) return Match::NotExpected;
    if (wait_.achk && address != wait_.address) return Match::OtherAddress;
    return Match::Accepted;
  }
  // A receive header waits: only then can offer() answer anything but NotExpected.
  bool waits_for_telegram() const { return wait_.waits; }
  // What would_take() compares with, kept current at every step of the walk (the receiver
  // reads it as data: ReceiveWants).
  const HeaderWait& wait() const { return wait_; }
  // An accepted telegram proved to be no list telegram (an MST): `item` waits again, as if
  // it had not been offered (its window may have closed meanwhile: then it is missed). If a
  // new cycle started since the offer, `item`'s cycle is over: it is missed, and the new
  // cycle's walk goes on as it is.
  void reclaim(const ListItem& item);
  // A fault the client found outside the walk (in an accepted telegram's containers, at its
  // detection): the list stops for the rest of the cycle, as for a fault found by the walk,
  // and the client is told (list_fault).
  void abort(const ListFault& fault) { this->fault(fault); }
  // What end_reached() does may have changed (INT_ENDMK cleared): a held end marker's event
  // is queued where it would have been.
  void end_may_change() {
    if (!end_held_) return;
    end_held_ = false;
    time_base_.queue_held(event_);
  }

 private:
  // Held: a receive header took an address-255 telegram, whose detection is awaited.
  enum class State : std::uint8_t { Idle, Transmit, Receive, Held, End };

  [[gnu::flatten]] void walk(std::uint16_t address);
  // offer(), taken(): `item` served, walk on.
  [[gnu::flatten]] void walk_past(const ListItem& item);
  void walk_from(const ListItem& first);
  bool arm(const ListItem& item);  // false: the item is already over, walk on
  bool arm_receive(const ListItem& item);
  void read_item(std::uint16_t address, ListItem& item);
  // Time-base actions (function + context: no std::function per armed item).
  static void transmit_time(void* list);
  static void end_time(void* list);
  static sim::Time end_step(void* list);  // a lazily held end marker's time (Scheduler::Resolve)
  [[gnu::flatten]] void fire_transmit();
  void close_window();
  void fire_end();
  // Mostly neither is armed (a receive header without TCHK waits, or the end marker ran).
  void cancel_event() {
    event_.cancel();
    end_held_ = false;
    cancel_window_judge();
  }
  void cancel_window_judge() {
    if (window_judge_.generation != 0) {  // EventId{}: none
      scheduler_.cancel(window_judge_);
      window_judge_ = {};
    }
  }
  void fault(const ListFault& fault);
  // Every change of state_ goes through these, so wait_ follows it.
  void set_state(State state) {
    state_ = state;
    wait_.waits = false;
  }
  // A receive header (item_) waits for a telegram: without TCHK at any time, with it
  // beginning in [opens, closes).
  void wait_for(const ListItem& item) {
    state_ = State::Receive;
    wait_.waits = true;
    wait_.tchk = false;
    wait_.achk = item.has(telegram::kAchk);
    wait_.address = item.adr();
  }
  void wait_for(const ListItem& item, sim::Time opens, sim::Time closes) {
    wait_for(item);
    wait_.tchk = true;
    wait_.opens = opens;
    wait_.closes = closes;
  }

  TimeBase& time_base_;
  sim::Scheduler& scheduler_;  // outlives the time base when units are destroyed
  TelegramRam& ram_;
  Client& client_;
  State state_ = State::Idle;
  ListItem item_;
  TimeBase::OwnedEvent event_;              // transmit or end marker due
  bool end_held_ = false;                   // event_ is an end marker held (hold_at_cycle_time)
  sim::Scheduler::EventId window_judge_{};  // a TCHK header's window is over
  HeaderWait wait_;  // state_ == Receive, and the header's window and address
  // Items the walk may still read in this cycle: every item takes at least two words, so a
  // walk reading more items than half the RAM has looped.
  std::uint32_t items_left_ = 0;
};

// The list of any ListClient (tests' clients), through its virtual functions.
using TelegramList = BasicTelegramList<ListClient>;
extern template class BasicTelegramList<ListClient>;

}  // namespace sercon::chip

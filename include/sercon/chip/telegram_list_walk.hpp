// The list walk's member functions (telegram_list.hpp), for the clients' translation units:
// TelegramList (any ListClient) is compiled in telegram_list.cpp, the telegram processor's
// list in telegram_processor.cpp, where its handlers inline into the walk.
#pragma once

#include <array>
#include <limits>

#include "sercon/chip/telegram_list.hpp"

namespace sercon::chip {

template <class Client>
BasicTelegramList<Client>::BasicTelegramList(TimeBase& time_base, TelegramRam& ram, Client& client)
    : time_base_(time_base),
      scheduler_(time_base.scheduler()),
      ram_(ram),
      client_(client),
      event_(time_base, this) {}

// The time base may already be gone when units are destroyed (its destructor cancels its
// own events); the scheduler outlives every chip.
template <class Client>
BasicTelegramList<Client>::~BasicTelegramList() {
  scheduler_.cancel(window_judge_);
}

template <class Client>
void BasicTelegramList<Client>::stop() {
  cancel_event();
  set_state(State::Idle);
}

template <class Client>
void BasicTelegramList<Client>::start(std::uint16_t list_pointer) {
  const State was = state_;
  stop();
  items_left_ = ram_.size() / 2u;
  if (was == State::Receive) {
    const ListItem waiting = item_;
    try {
      client_.receive_missed(waiting);
    } catch (const ListFault& f) {
      client_.list_fault(f);  // the old header's fault; the new cycle's walk still runs
    }
  }
  try {
    walk(telegram::pointer(ram_.read(list_pointer)));
  } catch (const ListFault& f) {
    fault(f);
  }
}

template <class Client>
void BasicTelegramList<Client>::fault(const ListFault& f) {
  stop();
  client_.list_fault(f);
}

// Fills `item` in place (a ListItem returned by value was assembled on the stack and
// reloaded whole: a store-forwarding stall per item).
template <class Client>
inline void BasicTelegramList<Client>::read_item(std::uint16_t address, ListItem& item) {
  if (items_left_ == 0) throw_list_fault("list loops (no end marker reached)");
  --items_left_;
  item.address = address;
  // Headers and end markers inside the RAM: looked at first, then their words (word 0 and
  // TRT, TLEN, PT or TEND, read in order by the general path below) marked as one run.
  if (address + telegram::kTransmitHeaderWords <= ram_.size()) {
    const std::uint16_t* words = ram_.words() + address;
    item.word0 = words[0];
    item.kind = telegram::kind_of(item.word0);
    item.time = words[telegram::kTimeWord];
    if (item.kind == telegram::Kind::EndMarker) {
      item.length = 0;
      item.next = 0;
      ram_.touch_checked_run(address, telegram::kEndMarkerWords);
      return;
    }
    if (item.kind != telegram::Kind::Invalid) {
      item.length = words[telegram::kLengthWord];
      item.next = telegram::pointer(words[telegram::kNextWord]);
      ram_.touch_checked_run(address, telegram::kTransmitHeaderWords);
      return;
    }
  }
  item = ListItem{};
  item.address = address;
  item.word0 = ram_.read(address);
  item.kind = telegram::kind_of(item.word0);
  switch (item.kind) {
    case telegram::Kind::Invalid:
      throw_list_fault("list item of kind 10 (neither header nor end marker)");
    case telegram::Kind::EndMarker:
      item.time = ram_.read(address + telegram::kTimeWord);
      return;
    case telegram::Kind::Receive:
    case telegram::Kind::Transmit: {
      std::array<std::uint16_t, 3> words{};  // TRT, TLEN, PT
      ram_.read_run(address + telegram::kTimeWord, words);
      item.time = words[0];
      item.length = words[1];
      item.next = telegram::pointer(words[2]);
      return;
    }
  }
}

// Arms items until one waits for something; items already over are settled on the way.
// A loop, not recursion: a long list of late items must not grow the stack. Each item is
// read straight into item_ (what it holds matters only while an item is armed).
// Flattened: arm() and the time base's event inline (a call per item otherwise); so are
// its callers start, fire_transmit and walk_past (offer, taken), each walking once a cycle.
template <class Client>
void BasicTelegramList<Client>::walk(std::uint16_t address) {
  for (;;) {
    read_item(address, item_);
    if (arm(item_) || item_.kind == telegram::Kind::EndMarker) return;
    address = item_.next;
  }
}

template <class Client>
void BasicTelegramList<Client>::walk_from(const ListItem& first) {
  item_ = first;
  if (!arm(item_) && item_.kind != telegram::Kind::EndMarker) walk(item_.next);
}

template <class Client>
bool BasicTelegramList<Client>::arm(const ListItem& item) {
  switch (item.kind) {
    case telegram::Kind::Transmit:
      if (!time_base_.at_cycle_time(event_, item.time, &BasicTelegramList::transmit_time)) {
        set_state(State::Idle);
        return false;  // late: not sent in this cycle
      }
      set_state(State::Transmit);
      return true;
    case telegram::Kind::Receive:
      return arm_receive(item);
    case telegram::Kind::EndMarker: {
      // Mostly INT_ENDMK is latched: the event is held, not queued (end_may_change()), and
      // its time worked out only if asked (end_step). Late, end_reached() would change
      // nothing: the held event then never runs.
      if (client_.end_changes_nothing()) {
        time_base_.hold_at_cycle_time(event_, item.time, &BasicTelegramList::end_time,
                                      &BasicTelegramList::end_step);
        end_held_ = true;
        set_state(State::End);
        return true;
      }
      if (!time_base_.at_cycle_time(event_, item.time, &BasicTelegramList::end_time)) {
        set_state(State::Idle);
        client_.end_reached(item);
        return false;
      }
      end_held_ = false;
      set_state(State::End);
      return true;
    }
    case telegram::Kind::Invalid:
      break;
  }
  return false;
}

template <class Client>
bool BasicTelegramList<Client>::arm_receive(const ListItem& item) {
  if (!item.has(telegram::kTchk)) {
    wait_for(item);
    return true;
  }
  const auto opens = time_base_.time_of_cycle_time(item.time - kWindowUs);
  const auto closes = time_base_.time_of_cycle_time(item.time + kWindowUs);
  if (!closes) {  // the window is over already
    set_state(State::Idle);
    client_.receive_missed(item);
    return false;
  }
  // Armed after the step out of TRT - 2 (behind a later transmit header, say): the window
  // still opened at that step, not when the header was read (doc §5).
  wait_for(item,
           opens ? *opens
                 : time_base_.time_of_past_cycle_time(item.time - kWindowUs)
                       .value_or(std::numeric_limits<sim::Time>::min()),
           *closes);
  window_judge_ = scheduler_.at(*closes + client_.start_report_delay(), [this] {
    window_judge_ = {};
    close_window();
  });
  return true;
}

template <class Client>
void BasicTelegramList<Client>::transmit_time(void* list) {
  static_cast<BasicTelegramList*>(list)->fire_transmit();
}

template <class Client>
sim::Time BasicTelegramList<Client>::end_step(void* list) {
  auto* const self = static_cast<BasicTelegramList*>(list);
  return self->time_base_.resolve_held(self->event_);
}

template <class Client>
void BasicTelegramList<Client>::end_time(void* list) {
  static_cast<BasicTelegramList*>(list)->fire_end();
}

template <class Client>
void BasicTelegramList<Client>::fire_transmit() {
  set_state(State::Idle);
  const ListItem item = item_;
  try {
    client_.transmit_due(item);
    walk(item.next);
  } catch (const ListFault& f) {
    fault(f);
  }
  // offer() answered NotExpected while the transmit item was armed; only a receive
  // header now waiting can change that.
  if (state_ == State::Receive) client_.list_moved();
}

template <class Client>
void BasicTelegramList<Client>::close_window() {
  set_state(State::Idle);
  const ListItem item = item_;
  try {
    client_.receive_missed(item);
    walk(item.next);
  } catch (const ListFault& f) {
    fault(f);
  }
  client_.list_moved();
}

// No list_moved(): offer() answers NotExpected before (end marker armed) and after.
template <class Client>
void BasicTelegramList<Client>::fire_end() {
  set_state(State::Idle);
  client_.end_reached(item_);
}

// offer() and taken(): the header `item` is served, the walk goes on behind it.
template <class Client>
void BasicTelegramList<Client>::walk_past(const ListItem& item) {
  set_state(State::Idle);
  try {
    walk(item.next);
  } catch (const ListFault& f) {
    fault(f);
  }
}

template <class Client>
void BasicTelegramList<Client>::reclaim(const ListItem& item) {
  if (state_ != State::Held || item_.address != item.address) {
    // A cycle start came while the telegram was under way: the header's cycle is over and
    // it got no list telegram in it, so it is missed as at that start; the new cycle's
    // walk is left alone.
    try {
      client_.receive_missed(item);
    } catch (const ListFault& f) {
      client_.list_fault(f);
    }
    return;
  }
  stop();
  try {
    walk_from(item);
  } catch (const ListFault& f) {
    fault(f);
  }
}

}  // namespace sercon::chip

#include "sercon/chip/telegram_list.hpp"

namespace sercon::chip {

using telegram::Kind;

TelegramList::TelegramList(TimeBase& time_base, TelegramRam& ram, ListClient& client)
    : time_base_(time_base), ram_(ram), client_(client) {}

// The time base may already be gone when units are destroyed; its destructor cancels its
// own events, so only a live event of ours needs cancelling, and only while it exists.
TelegramList::~TelegramList() = default;

void TelegramList::cancel_event() {
  if (event_ != 0) time_base_.cancel(event_);
  event_ = 0;
}

void TelegramList::stop() {
  cancel_event();
  state_ = State::Idle;
}

void TelegramList::start(std::uint16_t list_pointer) {
  const State was = state_;
  const ListItem waiting = item_;
  stop();
  items_read_ = 0;
  if (was == State::Receive) {
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

void TelegramList::fault(const ListFault& f) {
  stop();
  client_.list_fault(f);
}

ListItem TelegramList::read_item(std::uint16_t address) {
  // Every item takes at least two words, so a walk reading more items than half the RAM
  // has looped.
  if (++items_read_ > ram_.size() / 2u) throw ListFault("list loops (no end marker reached)");
  ListItem item;
  item.address = address;
  item.word0 = ram_.read(address);
  item.kind = telegram::kind_of(item.word0);
  switch (item.kind) {
    case Kind::Invalid:
      throw ListFault("list item of kind 10 (neither header nor end marker)");
    case Kind::EndMarker:
      item.time = ram_.read(address + telegram::kTimeWord);
      return item;
    case Kind::Receive:
    case Kind::Transmit:
      item.time = ram_.read(address + telegram::kTimeWord);
      item.length = ram_.read(address + telegram::kLengthWord);
      item.next = telegram::pointer(ram_.read(address + telegram::kNextWord));
      return item;
  }
  return item;
}

// Reads items until one waits for something; items already over are settled on the way.
// A loop, not recursion: a long list of late items must not grow the stack.
void TelegramList::walk(std::uint16_t address) {
  for (;;) {
    item_ = read_item(address);
    if (arm(item_)) return;
    if (item_.kind == Kind::EndMarker) return;
    address = item_.next;
  }
}

bool TelegramList::arm(const ListItem& item) {
  switch (item.kind) {
    case Kind::Transmit:
      event_ = time_base_.at_cycle_time(item.time, [this] { fire_transmit(); });
      state_ = event_ != 0 ? State::Transmit : State::Idle;
      return event_ != 0;  // late: not sent in this cycle
    case Kind::Receive: {
      state_ = State::Receive;
      if (!item.has(telegram::kTchk)) {
        window_opens_ = std::numeric_limits<sim::Time>::min();
        return true;
      }
      const auto opens = time_base_.time_of_cycle_time(item.time - kWindowUs);
      window_opens_ = opens ? *opens : std::numeric_limits<sim::Time>::min();
      event_ = time_base_.at_cycle_time(item.time + kWindowUs, [this] { close_window(); });
      if (event_ != 0) return true;
      state_ = State::Idle;
      client_.receive_missed(item);
      return false;
    }
    case Kind::EndMarker:
      event_ = time_base_.at_cycle_time(item.time, [this] { fire_end(); });
      state_ = event_ != 0 ? State::End : State::Idle;
      if (event_ == 0) client_.end_reached(item);
      return event_ != 0;
    case Kind::Invalid:
      break;
  }
  return false;
}

void TelegramList::fire_transmit() {
  event_ = 0;
  state_ = State::Idle;
  const ListItem item = item_;
  try {
    client_.transmit_due(item);
    walk(item.next);
  } catch (const ListFault& f) {
    fault(f);
  }
}

void TelegramList::close_window() {
  event_ = 0;
  state_ = State::Idle;
  const ListItem item = item_;
  try {
    client_.receive_missed(item);
    walk(item.next);
  } catch (const ListFault& f) {
    fault(f);
  }
}

void TelegramList::fire_end() {
  event_ = 0;
  state_ = State::Idle;
  client_.end_reached(item_);
}

TelegramList::Match TelegramList::offer(sim::Time start, std::uint8_t address, ListItem& item) {
  if (state_ != State::Receive) return Match::NotExpected;
  if (item_.has(telegram::kTchk)) {
    const auto closes = time_base_.when(event_);
    if (start < window_opens_ || !closes || start >= *closes) return Match::NotExpected;
  }
  if (item_.has(telegram::kAchk) && address != item_.adr()) return Match::OtherAddress;
  item = item_;
  cancel_event();
  state_ = State::Idle;
  try {
    walk(item.next);
  } catch (const ListFault& f) {
    fault(f);
  }
  return Match::Accepted;
}

}  // namespace sercon::chip

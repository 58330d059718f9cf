#include "sercon/chip/telegram_receive.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cstring>

namespace sercon::chip {

using telegram::kRerr;
using telegram::kVal;

void ReceivePath::withdraw(const ListItem& item, bool cleared) {
  if (!cleared) return;
  ram_.write(item.address, static_cast<std::uint16_t>(ram_.read(item.address) | kVal));
}

void ReceivePath::missed(const ListItem& item) {
  ram_.write(item.address, static_cast<std::uint16_t>(ram_.read(item.address) | kRerr));
  ram_.count_error(item.address + telegram::kNerrWord);
}

// The receiver writes bytes as they arrive and holds the last two back until the closing
// flag tells data from FCS; a frame cut off by an error never releases those two.
void ReceivePath::take_words(const wire::DecodedFrame& frame) {
  const bool whole =
      frame.error == wire::FrameError::None || frame.error == wire::FrameError::BadFcs;
  const std::size_t bytes =
      whole ? frame.data.size() : frame.data.size() - std::min<std::size_t>(2, frame.data.size());
  arrived_bytes_ = frame.data.data();
  arrived_words_ = bytes / 2;
}

// Words first .. last - 1 of those that arrived, little-endian on the line (facts §2),
// valid until the next call.
std::span<const std::uint16_t> ReceivePath::arrived(std::size_t first, std::size_t last) {
  static_assert(std::endian::native == std::endian::little);
  words_.resize(last - first);
  if (last > first) std::memcpy(words_.data(), arrived_bytes_ + 2 * first, 2 * (last - first));
  return words_;
}

ReceivePath::Outcome ReceivePath::finish(const ListItem& item, const wire::DecodedFrame& frame,
                                         ServiceChannelPort& port) {
  Outcome outcome;
  const bool error = !frame.ok() || frame.data.size() != 2u * item.length;
  outcome.error = error;
  take_words(frame);
  const std::uint16_t word0 = ram_.read(item.address);
  const bool val = (word0 & kVal) != 0;
  // Storage tested as bits of word 0 (a Storage would be built in a register).
  const bool double_buffer = (item.word0 & (telegram::kDma | telegram::kDbuf)) == telegram::kDbuf;
  // Word 0 as it will be written back, worked out from the word 0 read now before the
  // data goes in (fewer values kept across the stores).
  auto next = static_cast<std::uint16_t>(word0 & ~(kRerr | kVal));
  if (error) next |= kRerr;
  // Double buffer: VAL names the valid buffer and flips to the one just written when the
  // telegram was good. Single buffer and DMA: VAL says whether the data is good.
  const bool next_val = double_buffer ? (val != !error) : !error;
  if (next_val) next |= kVal;
  if (!item.has(telegram::kAchk)) {
    next = static_cast<std::uint16_t>((next & ~telegram::kAdrMask) | frame.address);
  }
  // Double buffer: the data goes into the buffer VAL does not name.
  outcome.service_work = store(item, double_buffer && !val, !error, port);
  ram_.write(item.address, next);
  if (error) ram_.count_error(item.address + telegram::kNerrWord);
  return outcome;
}

sim::Time ReceivePath::store(const ListItem& item, bool second_buffer, bool error_free,
                             ServiceChannelPort& port) {
  const std::uint32_t control = item.address + telegram::kReceiveHeaderWords;
  std::array<std::uint16_t, telegram::kReceiveContainerWords> head{};  // control, POS
  ram_.read_run(control, head);
  // Most telegrams have one plain container (no DMA, no service container): its words
  // straight into the buffer, without the general loop's set-up.
  if (item.has(telegram::kDma) || telegram::container_svfl(head[0]) ||
      !telegram::container_lastdc(head[0]))
    return store_containers(telegram::storage_of(item.word0), second_buffer, control, head,
                            error_free, port);
  const std::uint16_t len = telegram::container_len(head[0]);
  const std::size_t first = std::min<std::size_t>(head[1], arrived_words_);
  const std::size_t last = std::min<std::size_t>(std::size_t{head[1]} + len, arrived_words_);
  const std::uint32_t data = control + telegram::kReceiveContainerWords;
  ram_.write_run_le(second_buffer ? data + len : data, arrived_bytes_ + 2 * first, last - first);
  return 0;
}

// The general case: containers from the one at `control` (whose control word and POS
// were read as `head`) up to the one with LASTDC.
sim::Time ReceivePath::store_containers(telegram::Storage storage, bool second_buffer,
                                        std::uint32_t control, std::array<std::uint16_t, 2> head,
                                        bool error_free, ServiceChannelPort& port) {
  sim::Time work = 0;
  if (storage.dma) dma_words_.clear();
  for (std::uint32_t n = 0;; ++n) {
    if (n != 0) {
      if (n >= ram_.size()) throw_list_fault("receive containers without LASTDC");
      ram_.read_run(control, head);
    }
    // The control word's fields tested in place (a Container would be built in memory).
    const std::uint16_t len = telegram::container_len(head[0]);
    const std::uint16_t pos = head[1];
    const std::uint32_t data = control + telegram::kReceiveContainerWords;
    // The words of this container that arrived: POS .. POS + LEN of the telegram.
    const std::size_t first = std::min<std::size_t>(pos, arrived_words_);
    const std::size_t last = std::min<std::size_t>(std::size_t{pos} + len, arrived_words_);
    const std::uint32_t buffer = second_buffer ? data + len : data;
    if (!storage.dma && !telegram::container_svfl(head[0])) {  // straight into the buffer
      ram_.write_run_le(buffer, arrived_bytes_ + 2 * first, last - first);
    } else {
      work = std::max(work, store_through(storage.dma, head[0], control, buffer, first, last,
                                          error_free, port));
    }
    if (telegram::container_lastdc(head[0])) break;
    control = data + storage.buffer_words(len);
  }
  if (storage.dma) dma_.receive(dma_words_);
  return work;
}

// A DMA or service container: its words as a run, into the DMA words or the buffer, and
// handed to the service channel. Out of store()'s loop, which mostly takes plain buffers.
sim::Time ReceivePath::store_through(bool dma, std::uint16_t control_word, std::uint32_t control,
                                     std::uint32_t buffer, std::size_t first, std::size_t last,
                                     bool error_free, ServiceChannelPort& port) {
  const telegram::Container c = telegram::container_of(control_word);
  const std::span<const std::uint16_t> arrived = this->arrived(first, last);
  if (dma) {
    dma_words_.insert(dma_words_.end(), arrived.begin(), arrived.end());
  } else {
    ram_.write_run(buffer, arrived);
  }
  if (!c.svfl) return 0;
  const ServiceContainerUse use{c.nsv, c.scmaster, static_cast<std::uint16_t>(control),
                                static_cast<std::uint16_t>(dma ? 0 : buffer)};
  return port.after_receive(use, arrived, error_free);
}

}  // namespace sercon::chip

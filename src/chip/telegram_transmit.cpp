#include "sercon/chip/telegram_transmit.hpp"

#include <algorithm>
#include <bit>
#include <cstring>

namespace sercon::chip {

void TransmitPath::clear_send_once(const ListItem& item, bool val) {
  auto word0 = static_cast<std::uint16_t>(item.word0 & ~(telegram::kEn | telegram::kVal));
  if (val) word0 = static_cast<std::uint16_t>(word0 | telegram::kVal);
  ram_.write(item.address, word0);
}

// Single buffer, no DMA: the control words and data of the containers follow each other, so
// when every container is plain (no service container, within TLEN and the RAM) they are one
// run of words read in order. Looked at first without marks, then marked and counted as one
// run: the same words at the same instant as the general loop's reads, a few instructions
// per word instead of a read per container. Returns the words filled, or kNotARun (nothing
// read, nothing marked) for the general loop. Inline: called once, by gather().
inline std::size_t TransmitPath::gather_run(const ListItem& item) {
  std::uint32_t end = 0;
  const std::size_t filled = scan_run(item, end);
  if (filled == kNotARun) return kNotARun;
  const std::uint32_t first = item.address + telegram::kTransmitHeaderWords;
  ram_.touch_run(first, end - first);
  return filled;
}

// The words are laid out as they go on the line: little-endian words are the telegram's
// bytes in order (facts §2), so the containers are read straight into place.
std::span<const std::uint8_t> TransmitPath::gather(const ListItem& item, bool val,
                                                   ServiceChannelPort& port) {
  static_assert(std::endian::native == std::endian::little);
  const std::size_t total = item.length;
  words_.resize(total);  // each word written below: by a container, or as 0 at the end
  // Storage tested as bits of word 0 (a Storage would be built in a register).
  std::size_t filled =
      item.has(telegram::kDma) || item.has(telegram::kDbuf) ? kNotARun : gather_run(item);
  if (filled == kNotARun) filled = gather_containers(item, val, port);
  return laid_out(filled);
}

// The containers one by one, any storage: returns the words filled. Flattened: GCC made each
// container's TelegramRam::read_run a call.
[[gnu::flatten]] std::size_t TransmitPath::gather_containers(const ListItem& item, bool val,
                                                             ServiceChannelPort& port) {
  const bool dma = item.has(telegram::kDma);
  const bool dbuf = item.has(telegram::kDbuf);
  // Data words after a container's control word per data word: none with DMA, two
  // buffers with double buffering (Storage::buffer_words).
  const std::uint32_t buffers = dma ? 0 : (dbuf ? 2 : 1);
  // With double buffering VAL names the buffer that goes out (datasheet 4.2.1).
  const bool second_buffer = dbuf && val;
  const std::size_t total = item.length;
  std::size_t filled = 0;
  std::uint32_t control = item.address + telegram::kTransmitHeaderWords;
  // A container takes at least one word: more containers than RAM words is a loop.
  for (std::uint32_t n = 0;; ++n) {
    if (n >= ram_.size()) throw_list_fault("transmit containers without LASTDC");
    // The control word's fields tested in place (a Container would be built in memory).
    const std::uint16_t control_word = ram_.read(control);
    const std::uint16_t len = telegram::container_len(control_word);
    const std::uint32_t data = control + telegram::kTransmitContainerWords;
    const std::uint32_t buffer = second_buffer ? data + len : data;
    if (!dma && !telegram::container_svfl(control_word) && filled + len <= total) {
      ram_.read_run(buffer, std::span<std::uint16_t>(words_.data() + filled, len));
    } else {
      take(dma, control_word, control, buffer, filled, port);
    }
    filled += len;
    if (telegram::container_lastdc(control_word)) break;
    control = data + buffers * len;
  }
  return filled;
}

// A DMA or service container, or one reaching beyond TLEN (through a scratch buffer, cut
// to fit), into words_ from `filled` on. Out of gather()'s loop, which mostly takes plain
// buffers.
void TransmitPath::take(bool dma, std::uint16_t control_word, std::uint32_t control,
                        std::uint32_t buffer, std::size_t filled, ServiceChannelPort& port) {
  const telegram::Container c = telegram::container_of(control_word);
  const std::size_t total = words_.size();
  const bool fits = filled + c.len <= total;
  std::span<std::uint16_t> words;
  if (fits) {
    words = std::span<std::uint16_t>(words_.data() + filled, c.len);
  } else {
    container_.resize(c.len);
    words = container_;
  }
  if (dma) {
    dma_.transmit(words);
  } else {
    ram_.read_run(buffer, words);
  }
  if (c.svfl) {
    const ServiceContainerUse use{c.nsv, c.scmaster, static_cast<std::uint16_t>(control),
                                  static_cast<std::uint16_t>(dma ? 0 : buffer)};
    port.before_transmit(use, words);
  }
  // The part inside TLEN, if any: past it (or with TLEN = 0, words_ unallocated) no
  // position in words_ is formed.
  if (!fits && filled < total) {
    const std::size_t take = std::min<std::size_t>(c.len, total - filled);
    std::copy_n(container_.begin(), take, words_.begin() + static_cast<std::ptrdiff_t>(filled));
  }
}

}  // namespace sercon::chip

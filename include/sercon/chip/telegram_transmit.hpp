// The start of an own list telegram (datasheet 4.2.1/4.2.2; delta spec 2.10.1;
// docs/telegram-processing.md, "Transmit"): VAL is read again from word 0, a send-once
// header is written back with EN = 0 and that VAL, and the data words are gathered from
// the transmit containers (single buffer, the VAL buffer of a double buffer, or the DMA
// transmit FIFO), passed through the service channel port where SVFL = 1, and laid out as
// TLEN little-endian words.
#pragma once

#include <algorithm>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <span>
#include <vector>

#include "sercon/chip/dma_port.hpp"
#include "sercon/chip/service_channel_port.hpp"
#include "sercon/chip/telegram_list.hpp"
#include "sercon/chip/telegram_ram.hpp"

namespace sercon::chip {

class TransmitPath {
 public:
  TransmitPath(TelegramRam& ram, DmaPort& dma) : ram_(ram), dma_(dma) {}

  // Delta spec 2.10.1: VAL as word 0 holds it now, not as it was when the header was read.
  bool reread_val(const ListItem& item) { return (ram_.read(item.address) & telegram::kVal) != 0; }
  // A send-once header (EN = 1): word 0 as read with the header, EN = 0 and VAL = `val`.
  void clear_send_once(const ListItem& item, bool val);
  // The telegram's data bytes (2 * TLEN), valid until the next call.
  std::span<const std::uint8_t> gather(const ListItem& item, bool val, ServiceChannelPort& port);
  // reread_val() and gather() for the usual telegram, at one instant: a single-buffer
  // header without DMA or EN whose containers are all plain (gather_run). Word 0 and the
  // container run are marked and counted in one go: the same words, values, BUSYN marks and
  // counts as the general calls (VAL is not needed: no EN to write back, no second buffer).
  // False for any other telegram, with nothing read or marked. `data` is valid until the
  // next call or the next RAM write (it may be the RAM's words). Inline: at every telegram
  // start of a list.
  bool gather_plain(const ListItem& item, std::span<const std::uint8_t>& data) {
    if (item.has(telegram::kEn | telegram::kDma | telegram::kDbuf)) return false;
    // Mostly (an AT) one container of TLEN words: they go out straight from the RAM, laid out
    // as on the line already (little-endian words), without a copy.
    static_assert(std::endian::native == std::endian::little);
    const std::uint32_t control = item.address + telegram::kTransmitHeaderWords;
    if (control < ram_.size()) {
      const std::uint16_t* const ram = ram_.words();
      const std::uint16_t control_word = ram[control];
      const std::uint16_t len = telegram::container_len(control_word);
      if (telegram::container_lastdc(control_word) && !telegram::container_svfl(control_word) &&
          len == item.length && control + 1 + len <= ram_.size()) {
        ram_.read_and_touch_run(item.address, static_cast<std::uint16_t>(control), 1u + len);
        data = {reinterpret_cast<const std::uint8_t*>(ram + control + 1), 2u * len};
        return true;
      }
    }
    // Mostly the size it had for the same header last cycle (resize() costs more than this).
    if (words_.size() != item.length) [[unlikely]]
      words_.resize(item.length);
    std::uint32_t end = 0;
    const std::size_t filled = scan_run(item, end);
    if (filled == kNotARun) return false;
    const std::uint32_t first = item.address + telegram::kTransmitHeaderWords;
    ram_.read_and_touch_run(item.address, static_cast<std::uint16_t>(first), end - first);
    data = laid_out(filled);
    return true;
  }

 private:
  static constexpr std::size_t kNotARun = static_cast<std::size_t>(-1);
  std::size_t gather_run(const ListItem& item);
  // gather_run's look at the RAM, nothing marked: the containers' words copied into words_
  // (TLEN of them); returns the words filled and sets `end` past the last container, or
  // kNotARun. Inline: gather_plain() and gather_run() are at every telegram start.
  std::size_t scan_run(const ListItem& item, std::uint32_t& end) {
    const std::uint16_t* ram = ram_.words();
    const std::uint32_t size = ram_.size();
    const std::size_t total = item.length;
    std::uint32_t control = item.address + telegram::kTransmitHeaderWords;
    std::size_t filled = 0;
    for (;;) {  // control grows by at least one word a container: no loop
      if (control >= size) return kNotARun;
      const std::uint16_t control_word = ram[control];
      const std::uint16_t len = telegram::container_len(control_word);
      if (telegram::container_svfl(control_word) || filled + len > total ||
          control + 1 + len > size)
        return kNotARun;
      copy_words(ram + control + 1, len, words_.data() + filled);
      filled += len;
      control += 1 + len;
      if (telegram::container_lastdc(control_word)) break;
    }
    end = control;
    return filled;
  }
  // A container's words: up to 3 inline (a library call would cost more than they do).
  static void copy_words(const std::uint16_t* from, std::size_t count, std::uint16_t* to) {
    switch (count) {
      case 3:
        to[2] = from[2];
        [[fallthrough]];
      case 2:
        to[1] = from[1];
        [[fallthrough]];
      case 1:
        to[0] = from[0];
        [[fallthrough]];
      case 0:
        return;
      default:
        std::memcpy(to, from, 2 * count);
    }
  }
  // words_ with the words from `filled` on as 0 (the containers did not supply them), as
  // the telegram's bytes.
  std::span<const std::uint8_t> laid_out(std::size_t filled) {
    if (filled < words_.size())
      std::fill(words_.begin() + static_cast<std::ptrdiff_t>(filled), words_.end(), 0);
    return {reinterpret_cast<const std::uint8_t*>(words_.data()), 2 * words_.size()};
  }
  std::size_t gather_containers(const ListItem& item, bool val, ServiceChannelPort& port);
  void take(bool dma, std::uint16_t control_word, std::uint32_t control, std::uint32_t buffer,
            std::size_t filled, ServiceChannelPort& port);

  TelegramRam& ram_;
  DmaPort& dma_;
  std::vector<std::uint16_t> words_;      // the telegram's words, TLEN of them
  std::vector<std::uint16_t> container_;  // a container cut at TLEN; keeps its capacity
};

}  // namespace sercon::chip

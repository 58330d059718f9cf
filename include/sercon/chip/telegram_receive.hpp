// A receive header at work (datasheet 4.2.1/4.2.2; docs/telegram-processing.md,
// "Receive"): VAL at the start and the end of the telegram, the data words stored by POS
// into the receive containers (single buffer, the invalid buffer of a double buffer, or
// the DMA receive FIFO), service containers handed on, RERR / NERR / ADR at the end; a
// header whose telegram did not come gets RERR and NERR + 1.
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <span>
#include <vector>

#include "sercon/chip/dma_port.hpp"
#include "sercon/chip/service_channel_port.hpp"
#include "sercon/chip/telegram_list.hpp"
#include "sercon/chip/telegram_ram.hpp"
#include "sercon/wire/decoder.hpp"

namespace sercon::chip {

class ReceivePath {
 public:
  struct Outcome {
    bool error = false;          // RERR: errored (FCS, framing, length)
    sim::Time service_work = 0;  // the longest service-container work it started
  };

  ReceivePath(TelegramRam& ram, DmaPort& dma) : ram_(ram), dma_(dma) {}

  // The telegram begins (its address is in): single buffer and DMA data become invalid.
  // Returns whether it cleared VAL. Inline: at every telegram a header takes.
  bool begin(const ListItem& item) {
    // Double buffer without DMA (Storage tested as bits of word 0).
    if ((item.word0 & (telegram::kDma | telegram::kDbuf)) == telegram::kDbuf) return false;
    const std::uint16_t word0 = ram_.update(item.address, [](std::uint16_t w) {
      return static_cast<std::uint16_t>(w & ~telegram::kVal);
    });
    return (word0 & telegram::kVal) != 0;
  }
  // The telegram proved to be an MST: VAL back as before begin().
  void withdraw(const ListItem& item, bool cleared);
  // The telegram has been detected, the usual one (finish() for any other: false, nothing
  // read or written). Inline: at every telegram a header takes. The usual telegram:
  // error-free and of TLEN words, for a single-buffer header without DMA
  // whose one container is plain (no service container) and inside the RAM. What the general
  // path does: word 0 read, the container's control word and POS read, its data written,
  // word 0 written with VAL set (and the address without ACHK). The words are looked at
  // first, then marked and counted: the container's as one run (read control word and POS,
  // written data), word 0 as the update it is. All at one instant, with nothing else
  // scheduled among the marks: the same BUSYN marks as one by one.
  bool finish_plain(const ListItem& item, const wire::DecodedFrame& frame) {
    const std::size_t words = item.length;
    if (frame.error != wire::FrameError::None || frame.data.size() != 2 * words ||
        (item.word0 & (telegram::kDma | telegram::kDbuf)) != 0)
      return false;
    const std::uint32_t control = item.address + telegram::kReceiveHeaderWords;
    const std::uint32_t data = control + telegram::kReceiveContainerWords;
    const std::uint32_t size = ram_.size();
    if (data > size) return false;
    std::uint16_t* const ram = ram_.words_to_write();
    const std::uint16_t head = ram[control];
    if (telegram::container_svfl(head) || !telegram::container_lastdc(head)) return false;
    const std::size_t pos = ram[control + 1];
    const std::size_t first = std::min(pos, words);
    // At most TLEN words: 16 bits, which also tells GCC the copy below is bounded.
    const auto count =
        static_cast<std::uint16_t>(std::min(pos + telegram::container_len(head), words) - first);
    if (data + count > size) return false;
    const std::uint8_t* const bytes = frame.data.data() + 2 * first;
    // Word 0 and the marks before the data: a byte copy may alias anything, and what they
    // need would be loaded again after it. The order cannot be seen: the data never overlaps
    // word 0, the marks go to their own array, and a BUSYN change the marks make runs no
    // reaction (BUSYN has none) and is told to watchers only at the end of the event.
    const bool achk = item.has(telegram::kAchk);
    const std::uint8_t address = frame.address;
    ram_.update_and_touch_run(
        item.address,
        [achk, address](std::uint16_t word0) {
          auto next = static_cast<std::uint16_t>((word0 & ~telegram::kRerr) | telegram::kVal);
          if (!achk) next = static_cast<std::uint16_t>((next & ~telegram::kAdrMask) | address);
          return next;
        },
        static_cast<std::uint16_t>(control), telegram::kReceiveContainerWords + count);
    switch (count) {  // mostly a few words: no library call
      case 3:
        std::memcpy(ram + data + 2, bytes + 4, 2);
        [[fallthrough]];
      case 2:
        std::memcpy(ram + data + 1, bytes + 2, 2);
        [[fallthrough]];
      case 1:
        std::memcpy(ram + data, bytes, 2);
        [[fallthrough]];
      case 0:
        break;
      default:
        std::memcpy(ram + data, bytes, 2 * count);
    }
    return true;
  }
  // The telegram has been detected (ended, or cut off by an error).
  Outcome finish(const ListItem& item, const wire::DecodedFrame& frame, ServiceChannelPort& port);
  // No telegram for the header in this cycle.
  void missed(const ListItem& item);

 private:
  void take_words(const wire::DecodedFrame& frame);
  std::span<const std::uint16_t> arrived(std::size_t first, std::size_t last);
  // Inline (defined in the .cpp, called once there): finish() and store() are one function.
  inline sim::Time store(const ListItem& item, bool second_buffer, bool error_free,
                         ServiceChannelPort& port);
  sim::Time store_containers(telegram::Storage storage, bool second_buffer, std::uint32_t control,
                             std::array<std::uint16_t, 2> head, bool error_free,
                             ServiceChannelPort& port);
  sim::Time store_through(bool dma, std::uint16_t control_word, std::uint32_t control,
                          std::uint32_t buffer, std::size_t first, std::size_t last,
                          bool error_free, ServiceChannelPort& port);

  TelegramRam& ram_;
  DmaPort& dma_;
  // The telegram's data words that arrived (in the frame being finished), as bytes.
  const std::uint8_t* arrived_bytes_ = nullptr;
  std::size_t arrived_words_ = 0;
  std::vector<std::uint16_t> words_;  // one container's words of them
  std::vector<std::uint16_t> dma_words_;
};

}  // namespace sercon::chip

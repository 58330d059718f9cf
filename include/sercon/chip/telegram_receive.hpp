// A receive header at work (datasheet 4.2.1/4.2.2; docs/telegram-processing.md,
// "Receive"): VAL at the start and the end of the telegram, the data words stored by POS
// into the receive containers (single buffer, the invalid buffer of a double buffer, or
// the DMA receive FIFO), service containers handed on, RERR / NERR / ADR at the end; a
// header whose telegram did not come gets RERR and NERR + 1.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
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

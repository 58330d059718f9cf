// The start of an own list telegram (datasheet 4.2.1/4.2.2; delta spec 2.10.1;
// docs/telegram-processing.md, "Transmit"): VAL is read again from word 0, a send-once
// header is written back with EN = 0 and that VAL, and the data words are gathered from
// the transmit containers (single buffer, the VAL buffer of a double buffer, or the DMA
// transmit FIFO), passed through the service channel port where SVFL = 1, and laid out as
// TLEN little-endian words.
#pragma once

#include <cstdint>
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

 private:
  static constexpr std::size_t kNotARun = static_cast<std::size_t>(-1);
  std::size_t gather_run(const ListItem& item);
  std::size_t gather_containers(const ListItem& item, bool val, ServiceChannelPort& port);
  void take(bool dma, std::uint16_t control_word, std::uint32_t control, std::uint32_t buffer,
            std::size_t filled, ServiceChannelPort& port);

  TelegramRam& ram_;
  DmaPort& dma_;
  std::vector<std::uint16_t> words_;      // the telegram's words, TLEN of them
  std::vector<std::uint16_t> container_;  // a container cut at TLEN; keeps its capacity
};

}  // namespace sercon::chip

#include "sercon/chip/telegram_transmit.hpp"

#include <algorithm>

namespace sercon::chip {

void TransmitPath::clear_send_once(const ListItem& item, bool val) {
  auto word0 = static_cast<std::uint16_t>(item.word0 & ~(telegram::kEn | telegram::kVal));
  if (val) word0 = static_cast<std::uint16_t>(word0 | telegram::kVal);
  ram_.write(item.address, word0);
}

std::span<const std::uint8_t> TransmitPath::gather(const ListItem& item, bool val,
                                                   ServiceChannelPort& port) {
  const telegram::Storage storage = telegram::storage_of(item.word0);
  const std::size_t total = item.length;
  bytes_.assign(2 * total, 0);  // words the containers do not supply go out as 0
  std::size_t filled = 0;
  std::uint32_t control = item.address + telegram::kTransmitHeaderWords;
  // A container takes at least one word: more containers than RAM words is a loop.
  for (std::uint32_t n = 0;; ++n) {
    if (n >= ram_.size()) throw ListFault("transmit containers without LASTDC");
    const telegram::Container c = telegram::container_of(ram_.read(control));
    const std::uint32_t data = control + telegram::kTransmitContainerWords;
    container_.resize(c.len);
    if (storage.dma) {
      dma_.transmit(container_);
    } else {
      const std::uint32_t buffer = data + (storage.dbuf && val ? c.len : 0u);
      ram_.read_run(buffer, container_);
    }
    if (c.svfl) {
      const ServiceContainerUse use{c.nsv, c.scmaster, static_cast<std::uint16_t>(control),
                                    static_cast<std::uint16_t>(storage.dma ? 0 : data)};
      port.before_transmit(use, container_);
    }
    const std::size_t take = std::min<std::size_t>(c.len, total - std::min(filled, total));
    for (std::size_t i = 0; i < take; ++i) {
      bytes_[2 * (filled + i)] = static_cast<std::uint8_t>(container_[i] & 0xFF);
      bytes_[2 * (filled + i) + 1] = static_cast<std::uint8_t>(container_[i] >> 8);
    }
    filled += c.len;
    if (c.lastdc) break;
    control = data + storage.buffer_words(c.len);
  }
  return bytes_;
}

}  // namespace sercon::chip

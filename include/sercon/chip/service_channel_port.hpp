// Where the telegram processor hands a data container with SVFL = 1 to the service-
// container engine (datasheet 4.2.2 SVFL/NSV/SCMASTER, 4.2.4; delta spec 2.10.2;
// docs/telegram-processing.md, "Service channel port"). The processor owns the DPRAM walk
// and the line; the engine owns what the service words mean.
#pragma once

#include <cstdint>
#include <span>

#include "sercon/sim/time.hpp"

namespace sercon::chip {

struct ServiceContainerUse {
  std::uint8_t number = 0;         // NSV: service container 0..7 (SCPTn at RAM word 2 + n)
  bool master = false;             // SCMASTER: master (1) or slave (0) coding
  std::uint16_t control_word = 0;  // RAM address of the data container's control word
  std::uint16_t data_address = 0;  // RAM address of the data words used (the buffer)
};

class ServiceChannelPort {
 public:
  virtual ~ServiceChannelPort() = default;

  // Before a transmit telegram leaves: `words` holds the container's data words as read
  // from the DPRAM (or the DMA FIFO); the engine may replace them (MDT control word and
  // info, AT status word and info). What it leaves there goes on the line.
  virtual void before_transmit(const ServiceContainerUse& use, std::span<std::uint16_t> words) = 0;

  // After a receive telegram ended: the container's words as received (already stored in
  // the DPRAM or the DMA FIFO); `error_free` is false for an errored telegram. Returns how
  // long the engine's work lasts from now; INT_RSCEND is raised when all containers of
  // the telegram are done (delta spec 2.10.2).
  virtual sim::Time after_receive(const ServiceContainerUse& use,
                                  std::span<const std::uint16_t> words, bool error_free) = 0;
};

// Until the service-container engine exists: words go out and are stored as they are, and
// the work takes no time.
class PassThroughServiceChannel final : public ServiceChannelPort {
 public:
  void before_transmit(const ServiceContainerUse&, std::span<std::uint16_t>) override {}
  sim::Time after_receive(const ServiceContainerUse&, std::span<const std::uint16_t>,
                          bool) override {
    return 0;
  }
};

}  // namespace sercon::chip

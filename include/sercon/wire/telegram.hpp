// A SERCOS II telegram as the frame carries it (sercos-facts §1): address, then data.
// The FCS is not stored; the encoder computes it, the decoder checks it.
#pragma once

#include <cstdint>
#include <vector>

namespace sercon::wire {

struct Telegram {
  std::uint8_t address = 0;
  std::vector<std::uint8_t> data;

  friend bool operator==(const Telegram&, const Telegram&) = default;
};

}  // namespace sercon::wire

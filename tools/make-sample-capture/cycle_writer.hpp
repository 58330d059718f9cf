// Places telegrams on a SERCOS line at times within communication cycles, filling the
// gaps with idle, the way a master's telegram lists do (sercos-facts §2, §5).
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>

#include "sercon/wire/encoder.hpp"
#include "sercon/wire/line_bits.hpp"

namespace sercon::sample {

class CycleWriter {
 public:
  // `bits_per_us`: 2, 4, 8 or 16; `lead_in_bits` of idle come before the first cycle.
  CycleWriter(unsigned bits_per_us, std::size_t lead_in_bits);

  // Starts a cycle of `cycle_us` at the end of the previous one and sends the MST.
  void begin_cycle(unsigned cycle_us, std::uint8_t phase);
  // A telegram `t_us` after the end of this cycle's MST (how T1 and T2 count, IDN 6 / 89).
  void send(unsigned t_us, std::uint8_t address, std::span<const std::uint8_t> data);
  // The same frame with its FCS inverted, which every receiver must reject.
  void send_corrupted(unsigned t_us, std::uint8_t address, std::span<const std::uint8_t> data);
  // Idle to the end of the last cycle plus `tail_bits`, and the whole line.
  wire::LineBits finish(std::size_t tail_bits);

 private:
  void idle_until(std::size_t bit);

  wire::LineEncoder encoder_;
  unsigned bits_per_us_;
  std::size_t cycle_start_ = 0;
  std::size_t cycle_end_ = 0;
  std::size_t mst_end_ = 0;
};

}  // namespace sercon::sample

// Frame check sequence of SERCOS II telegrams (sercos-facts §1): CRC-16/X.25, reflected
// polynomial 0x8408, initial value 0xFFFF, final XOR 0xFFFF, over address + data.
// The value is sent low byte first.
#pragma once

#include <cstdint>
#include <span>

namespace sercon::wire {

// FCS as transmitted (after the final XOR). fcs16({FF 00}) == 0xF087, sent as 87 F0.
std::uint16_t fcs16(std::span<const std::uint8_t> address_and_data);

// Incremental, table-driven form: feed bytes in line order, read value() at any time.
class Fcs16 {
 public:
  void update(std::uint8_t byte);
  void update(std::span<const std::uint8_t> bytes);
  // The FCS of everything fed so far, as transmitted.
  std::uint16_t value() const { return static_cast<std::uint16_t>(crc_ ^ 0xFFFFu); }
  void reset() { crc_ = 0xFFFF; }

 private:
  std::uint16_t crc_ = 0xFFFF;  // CRC register before the final XOR
};

}  // namespace sercon::wire

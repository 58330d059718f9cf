// The interface through which a functional unit (time base, watchdog, DIV_CLK, ...) takes
// part in the chip's resets. See the note at the top of chip.hpp for how a unit plugs in.
#pragma once

#include <cstdint>
#include <string_view>

namespace sercon::chip {

enum class ResetCause : std::uint8_t {
  PowerOn,   // the Chip was constructed
  Pin,       // RSTN went low
  Software,  // SWRST: 0x0002 written to register 0x01
  OutputsZ,  // OUTZ went high (datasheet Table 1: "the circuit is reset")
};

constexpr std::string_view to_string(ResetCause cause) {
  switch (cause) {
    case ResetCause::PowerOn:
      return "power-on";
    case ResetCause::Pin:
      return "RSTN";
    case ResetCause::Software:
      return "SWRST";
    case ResetCause::OutputsZ:
      return "OUTZ";
  }
  return "?";
}

class ChipUnit {
 public:
  virtual ~ChipUnit() = default;
  ChipUnit() = default;
  ChipUnit(const ChipUnit&) = delete;
  ChipUnit& operator=(const ChipUnit&) = delete;

  // The chip enters reset. The registers already hold their reset values (RegisterFile
  // ::reset() plus the pin-dependent bits). Cancel pending events, forget state and drive
  // this unit's outputs to their inactive level through Chip::set_output().
  virtual void reset(ResetCause cause) = 0;
  // The chip leaves reset (RSTN high, OUTZ low; at once after SWRST and power-on): start
  // what runs by itself. Register writes are refused while the chip is held in reset.
  virtual void release() {}
};

}  // namespace sercon::chip

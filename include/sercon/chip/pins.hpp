// Every signal pin of the SERCON816 (datasheet Table 1), with its direction, package
// pin number and internal pull resistor (datasheet 3.3, I_IL / I_IH rows).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string_view>

namespace sercon::chip {

// Order: data bus, address bus, bus control, DMA, bus mode straps, interrupts, serial
// interface, clocks and test. The C API's sercon_pin enum uses the same numbering.
enum class Pin : std::uint8_t {
  // clang-format off
  D0, D1, D2, D3, D4, D5, D6, D7, D8, D9, D10, D11, D12, D13, D14, D15,
  A0, A1, A2, A3, A4, A5, A6, A7, A8, A9, A10, A11, A12, A13, A14, A15,
  ALEL, ALEH, RDN, WRN, BHEN, MCSN0, MCSN1, PCSN0, PCS1, BUSYN,
  DMAREQR, DMAACKRN, DMAREQT, DMAACKTN,
  ADMUX, BUSMODE0, BUSMODE1, BUSWIDTH, BYTEDIR,
  INT0, INT1,
  SBAUD16, SBAUD, RxD, RxC, RECACTN, TxD1, TxD2, TxD3, TxD4, TxD5, TxD6, TxC, IDLE,
  TM0, TM1, WDOGN, L_ERRN, CYC_CLK, CON_CLK, DIV_CLK,
  SCLK, SCLKO2, SCLKO4, MCLK, RSTN, TEST, OUTZ, NDTRO,
  // clang-format on
};

inline constexpr std::size_t kPinCount = static_cast<std::size_t>(Pin::NDTRO) + 1;

enum class PinDirection : std::uint8_t {
  In,     // driven by the board
  Out,    // driven by the chip
  InOut,  // D15-0 (chip drives during reads), A15-0 (chip drives when ADMUX = 1)
};

// What an undriven (high impedance) input reads as.
enum class Pull : std::uint8_t { None, Up, Down };

struct PinInfo {
  std::string_view name;
  PinDirection direction;
  std::uint8_t package_pin;  // QFP100 pin; 0 where Table 1 does not give it (A15-0)
  Pull pull;
};

const PinInfo& pin_info(Pin pin);
inline std::string_view pin_name(Pin pin) { return pin_info(pin).name; }
// Looks a pin up by its Table 1 name (exact, case-sensitive: "TxD1", "CYC_CLK").
std::optional<Pin> find_pin(std::string_view name);

constexpr std::size_t index_of(Pin pin) { return static_cast<std::size_t>(pin); }
constexpr Pin pin_at(std::size_t index) { return static_cast<Pin>(index); }
constexpr Pin data_pin(unsigned bit) { return pin_at(index_of(Pin::D0) + bit); }
constexpr Pin address_pin(unsigned bit) { return pin_at(index_of(Pin::A0) + bit); }
constexpr Pin txd_pin(unsigned n) { return pin_at(index_of(Pin::TxD1) + n - 1); }  // n = 1..6

}  // namespace sercon::chip

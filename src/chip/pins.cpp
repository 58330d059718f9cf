#include "sercon/chip/pins.hpp"

#include <stdexcept>
#include <string>

namespace sercon::chip {
namespace {

using enum PinDirection;
using enum Pull;

// Index == Pin value. Package pins and directions: datasheet Table 1; pulls: datasheet 3.3.
constexpr std::array<PinInfo, kPinCount> kPins = {{
    {"D0", InOut, 95, Up},      {"D1", InOut, 94, Up},      {"D2", InOut, 93, Up},
    {"D3", InOut, 92, Up},      {"D4", InOut, 90, Up},      {"D5", InOut, 89, Up},
    {"D6", InOut, 88, Up},      {"D7", InOut, 87, Up},      {"D8", InOut, 85, Up},
    {"D9", InOut, 84, Up},      {"D10", InOut, 83, Up},     {"D11", InOut, 82, Up},
    {"D12", InOut, 80, Up},     {"D13", InOut, 79, Up},     {"D14", InOut, 78, Up},
    {"D15", InOut, 77, Up},     {"A0", InOut, 0, Up},       {"A1", InOut, 0, Up},
    {"A2", InOut, 0, Up},       {"A3", InOut, 0, Up},       {"A4", InOut, 0, Up},
    {"A5", InOut, 0, Up},       {"A6", InOut, 0, Up},       {"A7", InOut, 0, Up},
    {"A8", InOut, 0, Up},       {"A9", InOut, 0, Up},       {"A10", InOut, 0, Up},
    {"A11", InOut, 0, Up},      {"A12", InOut, 0, Up},      {"A13", InOut, 0, Up},
    {"A14", InOut, 0, Up},      {"A15", InOut, 0, Up},      {"ALEL", In, 54, Down},
    {"ALEH", In, 53, Down},     {"RDN", In, 51, None},      {"WRN", In, 52, None},
    {"BHEN", In, 75, Up},       {"MCSN0", In, 46, Up},      {"MCSN1", In, 47, Up},
    {"PCSN0", In, 48, Up},      {"PCS1", In, 49, Up},       {"BUSYN", Out, 45, None},
    {"DMAREQR", Out, 38, None}, {"DMAACKRN", In, 40, Up},   {"DMAREQT", Out, 39, None},
    {"DMAACKTN", In, 41, Up},   {"ADMUX", In, 96, Up},      {"BUSMODE0", In, 97, Up},
    {"BUSMODE1", In, 98, Up},   {"BUSWIDTH", In, 99, None}, {"BYTEDIR", In, 100, Up},
    {"INT0", Out, 44, None},    {"INT1", Out, 43, None},    {"SBAUD16", In, 28, Up},
    {"SBAUD", In, 29, Up},      {"RxD", In, 14, Up},        {"RxC", Out, 12, None},
    {"RECACTN", Out, 26, None}, {"TxD1", Out, 16, Up},      {"TxD2", Out, 17, Up},
    {"TxD3", Out, 18, Up},      {"TxD4", Out, 20, Up},      {"TxD5", Out, 21, Up},
    {"TxD6", Out, 22, Up},      {"TxC", Out, 13, None},     {"IDLE", Out, 25, None},
    {"TM0", In, 30, Up},        {"TM1", In, 31, Up},        {"WDOGN", Out, 24, None},
    {"L_ERRN", Out, 32, None},  {"CYC_CLK", In, 34, Up},    {"CON_CLK", Out, 35, None},
    {"DIV_CLK", Out, 36, None}, {"SCLK", In, 2, Down},      {"SCLKO2", Out, 6, None},
    {"SCLKO4", Out, 5, None},   {"MCLK", In, 4, Down},      {"RSTN", In, 10, Down},
    {"TEST", In, 7, Up},        {"OUTZ", In, 11, Up},       {"NDTRO", Out, 9, None},
}};

}  // namespace

const PinInfo& pin_info(Pin pin) {
  const auto index = index_of(pin);
  if (index >= kPinCount) {
    throw std::out_of_range("pin_info: no pin with number " + std::to_string(index));
  }
  return kPins[index];
}

std::optional<Pin> find_pin(std::string_view name) {
  for (std::size_t i = 0; i < kPinCount; ++i) {
    if (kPins[i].name == name) return pin_at(i);
  }
  return std::nullopt;
}

}  // namespace sercon::chip

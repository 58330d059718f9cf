#include "sercon/chip/interrupts.hpp"

#include <utility>

#include "sercon/chip/chip.hpp"

namespace sercon::chip {
namespace {

constexpr std::uint8_t kIntStat = 0x04;
constexpr std::uint8_t kIntSc = 0x05;
constexpr std::uint8_t kIen0A = 0x06;
constexpr std::uint8_t kIen1A = 0x07;
constexpr std::uint8_t kIen0B = 0x08;
constexpr std::uint8_t kIen1B = 0x09;
constexpr std::uint8_t kWdCtrl = 0x28;  // INT_WDOG, INT_RSCEND and their enables

constexpr std::string_view kFlagNames[kIrqCount] = {
    "INT_RDIST",  "INT_FIBBR",    "INT_CYCST",   "INT_REND",    "INT_TEND",   "INT_RERR",
    "INT_ENDMK",  "INT_MSTEARLY", "INT_MSTLATE", "INT_MSTMISS", "INT_RETMST", "INT_CONCLK",
    "INT_DIVCLK", "INT_DMAERR",   "INT_WDOG",    "INT_RSCEND",
};

}  // namespace

Interrupts::Interrupts(Chip& chip)
    : Interrupts(
          chip.regs(), [&chip](bool high) { chip.set_output(Pin::INT0, high); },
          [&chip](bool high) { chip.set_output(Pin::INT1, high); }) {}

Interrupts::Interrupts(RegisterFile& regs, Output int0, Output int1)
    : regs_(regs), int0_(std::move(int0)), int1_(std::move(int1)) {
  const Variant v = regs.variant();
  for (std::size_t i = 0; i < kIrqCount; ++i) flags_[i] = field_ref(kFlagNames[i], v);
  en0_wdog_ = field_ref("EN0_INT_WDOG", v);
  en1_wdog_ = field_ref("EN1_INT_WDOG", v);
  en0_rscend_ = field_ref("EN0_INT_RSCEND", v);
  en1_rscend_ = field_ref("EN1_INT_RSCEND", v);
  int0pol_ = field_ref("INT0POL", v);
  int1pol_ = field_ref("INT1POL", v);
  const std::uint8_t polarity = int0pol_.address;
  regs_.on_change([this, polarity](std::uint8_t address) {
    const bool routed =
        address == polarity || (address >= kIntStat && address <= kIen1B) || address == kWdCtrl;
    // A reset's values are driven by reset(), once all of them are in (INTxPOL is reset
    // before the latches: no pulse out of the half-reset registers).
    for (const ClearWatch& w : clear_watches_) {
      if (address == field(w.source).address && !latched(w.source)) w.listener(w.context);
    }
    if (routed && !regs_.resetting()) refresh();
  });
}

void Interrupts::on_clear(Irq source, ClearListener listener, void* context) {
  clear_watches_.push_back(ClearWatch{source, listener, context});
}

void Interrupts::reset(ResetCause) { refresh(); }

void Interrupts::set_level(Irq source, bool high) {
  const FieldRef& f = field(source);
  if (high) f.set(regs_, true);
  regs_.hold(f.address, f.mask, high);
}

void Interrupts::raise_service_container(unsigned container) {
  if (container < 8) regs_.set_bits(kIntSc, static_cast<std::uint16_t>(1u << container), true);
}

bool Interrupts::requesting(int output) const {
  const std::uint16_t ena = regs_.value(output == 0 ? kIen0A : kIen1A);
  const std::uint16_t enb = regs_.value(output == 0 ? kIen0B : kIen1B);
  if ((regs_.value(kIntStat) & ena) != 0 || (regs_.value(kIntSc) & enb) != 0) return true;
  const FieldRef& en_wdog = output == 0 ? en0_wdog_ : en1_wdog_;
  const FieldRef& en_rscend = output == 0 ? en0_rscend_ : en1_rscend_;
  return (latched(Irq::Wdog) && en_wdog.on(regs_)) || (latched(Irq::Rscend) && en_rscend.on(regs_));
}

// INTxPOL = 0: active high; 1: active low (register table, 0x03).
void Interrupts::refresh() {
  int0_(requesting(0) != int0pol_.on(regs_));
  int1_(requesting(1) != int1pol_.on(regs_));
}

}  // namespace sercon::chip

// Interrupt latches and the INT0/INT1 outputs. Every source is a latched bit: INTSTAT
// (0x04), INTSC (0x05, one bit per service container), INT_WDOG and INT_RSCEND in WDCTRL
// (0x28). All are cleared by writing 1 (the register file's W1C rule). Each is routed
// separately to INT0 and INT1 (IEN0A/IEN1A 0x06/0x07, IEN0B/IEN1B 0x08/0x09, EN0/EN1 bits
// of 0x28), and each output has its polarity (INT0POL/INT1POL in 0x03). The pins follow
// every change of those registers at once.
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include "sercon/chip/chip_unit.hpp"
#include "sercon/chip/field_ref.hpp"
#include "sercon/chip/register_file.hpp"

namespace sercon::chip {

class Chip;

// The sources other units raise. The INTSTAT bits follow the register table.
enum class Irq : std::uint8_t {
  Rdist,     // INT_RDIST
  Fibbr,     // INT_FIBBR
  Cycst,     // INT_CYCST
  Rend,      // INT_REND
  Tend,      // INT_TEND
  Rerr,      // INT_RERR
  Endmk,     // INT_ENDMK
  MstEarly,  // INT_MSTEARLY
  MstLate,   // INT_MSTLATE
  MstMiss,   // INT_MSTMISS
  RetMst,    // INT_RETMST
  ConClk,    // INT_CONCLK
  DivClk,    // INT_DIVCLK
  DmaErr,    // INT_DMAERR
  Wdog,      // INT_WDOG (816 only)
  Rscend,    // INT_RSCEND (816 only; the service-container engine raises it)
};
inline constexpr std::size_t kIrqCount = static_cast<std::size_t>(Irq::Rscend) + 1;

class Interrupts : public ChipUnit {
 public:
  using Output = std::function<void(bool high)>;

  explicit Interrupts(Chip& chip);
  Interrupts(RegisterFile& regs, Output int0, Output int1);

  void reset(ResetCause cause) override;

  // Latches `source`. A source the variant lacks (INT_WDOG, INT_RSCEND on the 410B) is
  // ignored. Inline: a ring raises some sixty a cycle, nearly all of them latched already.
  void raise(Irq source) { field(source).set(regs_, true); }
  // A source that is a level (INT_RDIST: RDIST, INT_FIBBR: FIBBR): high latches the flag and
  // keeps a write of 1 from clearing it while the level stays high; low lets it be cleared
  // (docs/serial-and-ring.md, "Line monitor").
  void set_level(Irq source, bool high);
  // Latches INTSC bit `container` (0..7); larger numbers are ignored.
  void raise_service_container(unsigned container);

  bool latched(Irq source) const { return field(source).on(regs_); }
  // `listener(context)` after every change of `source`'s register that leaves its flag
  // clear (a write of 1, a reset): for a unit that leaves out an event that would only
  // raise the flag while it is latched. `context` must outlive the Interrupts.
  using ClearListener = void (*)(void* context);
  void on_clear(Irq source, ClearListener listener, void* context);
  bool int0_active() const { return requesting(0); }
  bool int1_active() const { return requesting(1); }

 private:
  const FieldRef& field(Irq source) const { return flags_[static_cast<std::size_t>(source)]; }
  bool requesting(int output) const;
  void refresh();

  RegisterFile& regs_;
  Output int0_;
  Output int1_;
  FieldRef flags_[kIrqCount];
  FieldRef en0_wdog_, en1_wdog_, en0_rscend_, en1_rscend_;
  FieldRef int0pol_, int1pol_;
  struct ClearWatch {
    Irq source;
    ClearListener listener;
    void* context;
  };
  std::vector<ClearWatch> clear_watches_;
};

}  // namespace sercon::chip

// The chip's functional units, in construction and reset order (see chip.hpp, "How a
// unit plugs in"). One line per unit; a unit's header is included here only.
#include "sercon/chip/chip.hpp"
#include "sercon/chip/con_clk.hpp"
#include "sercon/chip/cycle_control.hpp"
#include "sercon/chip/div_clk.hpp"
#include "sercon/chip/dma_port.hpp"
#include "sercon/chip/interrupts.hpp"
#include "sercon/chip/nand_tree.hpp"
#include "sercon/chip/pin_bus.hpp"
#include "sercon/chip/serial_unit.hpp"
#include "sercon/chip/telegram_processor.hpp"
#include "sercon/chip/time_base.hpp"
#include "sercon/chip/watchdog.hpp"

namespace sercon::chip {

void Chip::build_units() {
  add_unit<PinBus>();
  add_unit<NandTree>();
  // Timing (docs/timing.md); each needs the ones before it.
  add_unit<Interrupts>();
  add_unit<TimeBase>();
  add_unit<CycleControl>();
  add_unit<Watchdog>();
  add_unit<DivClk>();
  add_unit<ConClk>();
  add_unit<SerialUnit>();  // serial interface (docs/serial-and-ring.md)
  // Telegram processing (docs/telegram-processing.md).
  add_unit<DmaPort>();
  add_unit<TelegramProcessor>();
}

}  // namespace sercon::chip

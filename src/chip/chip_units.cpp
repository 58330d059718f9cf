// The chip's functional units, in construction and reset order (see chip.hpp, "How a
// unit plugs in"). One line per unit; a unit's header is included here only.
#include "sercon/chip/chip.hpp"
#include "sercon/chip/nand_tree.hpp"
#include "sercon/chip/pin_bus.hpp"

namespace sercon::chip {

void Chip::build_units() {
  add_unit<PinBus>();
  add_unit<NandTree>();
}

}  // namespace sercon::chip

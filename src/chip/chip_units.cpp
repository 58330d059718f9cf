// The chip's functional units, in construction and reset order (see chip.hpp, "How a
// unit plugs in"). One line per unit; a unit's header is included here only.
#include "sercon/chip/chip.hpp"

namespace sercon::chip {

void Chip::build_units() {
  // Units are appended here, e.g. add_unit<TimeBase>();
}

}  // namespace sercon::chip

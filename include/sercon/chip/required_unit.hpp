// Finds a unit another unit depends on (e.g. the watchdog needs the time base). Units
// are built in the order of Chip::build_units(), so a dependency must come earlier there.
#pragma once

#include <stdexcept>
#include <string>
#include <string_view>

#include "sercon/chip/chip.hpp"

namespace sercon::chip {

template <typename T>
T& required_unit(Chip& chip, std::string_view needed_by) {
  if (T* unit = chip.unit<T>()) return *unit;
  throw std::logic_error(std::string(needed_by) +
                         " needs a unit built before it in Chip::build_units()");
}

}  // namespace sercon::chip

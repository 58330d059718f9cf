// A chip on a scheduler, built from a config: the starting point of most chip tests.
#pragma once

#include <memory>

#include "sercon/chip/chip.hpp"
#include "sercon/sim/scheduler.hpp"

namespace sercon::chip::testing {

struct ChipOnBench {
  explicit ChipOnBench(const ChipConfig& config = {})
      : chip(std::make_unique<Chip>(scheduler, config)) {}
  sim::Scheduler scheduler;
  std::unique_ptr<Chip> chip;
};

inline ChipConfig config_410b() {
  ChipConfig c;
  c.variant = Variant::Sercon410B;
  c.sbaud16 = true;  // SREGEN tied high: internal clock recovery (delta spec 2.3.2)
  return c;
}

}  // namespace sercon::chip::testing

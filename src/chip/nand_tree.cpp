#include "sercon/chip/nand_tree.hpp"

#include "sercon/chip/chip.hpp"

namespace sercon::chip {
namespace {

bool in_tree(Pin p) { return pin_info(p).direction != PinDirection::Out; }

}  // namespace

NandTree::NandTree(Chip& chip) : chip_(chip) {
  for (std::size_t i = 0; i < kPinCount; ++i) {
    if (in_tree(pin_at(i))) chip_.pin(pin_at(i)).watch([this](sim::Level) { update(); });
  }
}

void NandTree::reset(ResetCause) { update(); }

void NandTree::update() {
  bool started = false;
  bool t = false;
  for (std::size_t i = 0; i < kPinCount; ++i) {
    const Pin p = pin_at(i);
    if (!in_tree(p)) continue;
    const bool in = chip_.input_high(p);
    t = started ? !(t && in) : in;
    started = true;
  }
  chip_.set_output(Pin::NDTRO, t);
}

}  // namespace sercon::chip

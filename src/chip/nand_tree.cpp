#include "sercon/chip/nand_tree.hpp"

#include "sercon/chip/chip.hpp"

namespace sercon::chip {

NandTree::NandTree(Chip& chip) : chip_(chip) {
  for (std::size_t i = 0; i < kPinCount; ++i) {
    if (pin_info(pin_at(i)).direction != PinDirection::Out) inputs_.push_back(pin_at(i));
  }
  stages_.assign(inputs_.size(), false);
  for (std::size_t k = 0; k < inputs_.size(); ++k) {
    stages_[k] = stage(k);
    chip_.pin(inputs_[k]).react([this, k](sim::Level) { update_from(k); });
  }
}

void NandTree::reset(ResetCause) {
  for (std::size_t k = 0; k < inputs_.size(); ++k) stages_[k] = stage(k);
  chip_.set_output(Pin::NDTRO, stages_.back());
}

bool NandTree::stage(std::size_t k) const {
  const bool in = chip_.input_high(inputs_[k]);
  return k == 0 ? in : !(stages_[k - 1] && in);
}

// Input k changed: stages from k on may change; once one keeps its value, the rest do.
void NandTree::update_from(std::size_t k) {
  for (; k < inputs_.size(); ++k) {
    const bool next = stage(k);
    if (next == stages_[k]) return;
    stages_[k] = next;
  }
  chip_.set_output(Pin::NDTRO, stages_.back());
}

}  // namespace sercon::chip

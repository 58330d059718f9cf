// NDTRO, the NAND tree output for the board connection test (datasheet Table 1). The
// datasheet does not give the order of the tree's inputs; this model chains every input
// and bidirectional pin in Pin order: t = in(first); t = NAND(t, in(next)) ...; NDTRO = t.
// NDTRO keeps driving while OUTZ = 1, as the datasheet says. Each stage's output is kept,
// so an input change re-evaluates only the stages it reaches.
#pragma once

#include <cstddef>
#include <vector>

#include "sercon/chip/chip_unit.hpp"
#include "sercon/chip/pins.hpp"

namespace sercon::chip {

class Chip;

class NandTree : public ChipUnit {
 public:
  explicit NandTree(Chip& chip);
  void reset(ResetCause cause) override;

 private:
  bool stage(std::size_t k) const;
  void update_from(std::size_t k);

  Chip& chip_;
  std::vector<Pin> inputs_;   // tree order
  std::vector<bool> stages_;  // stages_[k]: output of stage k; the last drives NDTRO
};

}  // namespace sercon::chip

// NDTRO, the NAND tree output for the board connection test (datasheet Table 1). The
// datasheet does not give the order of the tree's inputs; this model chains every input
// and bidirectional pin in Pin order: t = in(first); t = NAND(t, in(next)) ...; NDTRO = t.
// NDTRO keeps driving while OUTZ = 1, as the datasheet says.
#pragma once

#include "sercon/chip/chip_unit.hpp"

namespace sercon::chip {

class Chip;

class NandTree : public ChipUnit {
 public:
  explicit NandTree(Chip& chip);
  void reset(ResetCause cause) override;

 private:
  void update();
  Chip& chip_;
};

}  // namespace sercon::chip

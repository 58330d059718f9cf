// The register fields the serial unit reads and writes (0x01 SERMODE, 0x02 SERCTRL, 0x0B
// TXPORT, 0x0D LINEMON), resolved once from the register table.
#pragma once

#include "sercon/chip/field_ref.hpp"
#include "sercon/chip/variant.hpp"

namespace sercon::chip {

struct SerialFields {
  explicit SerialFields(Variant variant);

  FieldRef repon, poltxd;                  // 0x01
  FieldRef txoe, txlight, ledist, lemiss;  // 0x02 control
  FieldRef rdist, fibbr, recact;           // 0x02 status
  FieldRef portsel, portval;               // 0x0B
  FieldRef rdistlim, fibbrtim;             // 0x0D
};

}  // namespace sercon::chip

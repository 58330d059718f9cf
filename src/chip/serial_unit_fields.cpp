#include "sercon/chip/serial_unit_fields.hpp"

namespace sercon::chip {

SerialFields::SerialFields(Variant v)
    : repon(field_ref("REPON", v)),
      poltxd(field_ref("POLTXD", v)),
      txoe(field_ref("TXOE", v)),
      txlight(field_ref("TXLIGHT", v)),
      ledist(field_ref("LEDIST", v)),
      lemiss(field_ref("LEMISS", v)),
      rdist(field_ref("RDIST", v)),
      fibbr(field_ref("FIBBR", v)),
      recact(field_ref("RECACT", v)),
      portsel(field_ref("PORTSEL", v)),
      portval(field_ref("PORTVAL", v)),
      rdistlim(field_ref("RDISTLIM", v)),
      fibbrtim(field_ref("FIBBRTIM", v)) {}

}  // namespace sercon::chip

#include "sercon/chip/field_ref.hpp"

#include <stdexcept>
#include <string>

#include "sercon/chip/register_map.hpp"

namespace sercon::chip {
namespace {

bool present_in(Variants variants, Variant variant) {
  switch (variants) {
    case Variants::Both:
      return true;
    case Variants::Only816:
      return variant == Variant::Sercon816;
    case Variants::Only410B:
      return variant == Variant::Sercon410B;
  }
  return false;
}

}  // namespace

FieldRef field_ref(std::string_view name, Variant variant) {
  bool known = false;
  for (const RegisterInfo& reg : register_map()) {
    for (const BitField& field : reg.fields) {
      if (field.name != name) continue;
      known = true;
      if (present_in(field.variants, variant))
        return FieldRef{reg.address, field.mask(), field.lsb};
    }
  }
  if (!known)
    throw std::invalid_argument("field_ref: no register field named " + std::string(name));
  return FieldRef{};
}

}  // namespace sercon::chip

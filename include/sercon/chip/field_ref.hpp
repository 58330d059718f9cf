// A named field of the register table, resolved once to its address and mask, so that
// units read and write fields by name without repeating bit positions (the table stays the
// single source of truth).
#pragma once

#include <cstdint>
#include <string_view>

#include "sercon/chip/register_file.hpp"
#include "sercon/chip/variant.hpp"

namespace sercon::chip {

struct FieldRef {
  std::uint8_t address = 0;
  std::uint16_t mask = 0;  // 0: the field does not exist in this variant
  std::uint8_t lsb = 0;

  bool present() const { return mask != 0; }
  std::uint16_t get(const RegisterFile& regs) const {
    return static_cast<std::uint16_t>((regs.field_value(address) & mask) >> lsb);
  }
  bool on(const RegisterFile& regs) const { return (regs.field_value(address) & mask) != 0; }
  // Chip-side writes (status bits, watchdog clearing ENTMT/PHAS0); no-ops when absent
  // (mask 0 changes no bit, so put_field returns at once: no test of present() needed).
  void put(RegisterFile& regs, std::uint16_t value) const {
    regs.put_field(address, mask, static_cast<std::uint16_t>(value << lsb));
  }
  void set(RegisterFile& regs, bool on) const { regs.set_field_bits(address, mask, on); }
};

// The field called `name` in `variant`; a FieldRef with mask 0 when the variant lacks it
// (e.g. the watchdog fields on the 410B). Throws std::invalid_argument for a name the table
// does not know in any variant (a typo in the model, not a runtime condition).
FieldRef field_ref(std::string_view name, Variant variant);

}  // namespace sercon::chip

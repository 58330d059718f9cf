// The SERCON816 / SERCON410B control-register map (word addresses 0x00..0x2A) as data:
// the single source of truth for access rules, reset values and docs/registers.md.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string_view>

#include "sercon/chip/variant.hpp"

namespace sercon::chip {

inline constexpr std::uint8_t kRegisterCount = 0x2B;  // 0x00..0x2A

enum class Access : std::uint8_t {
  R,    // status: writes are ignored
  RW,   // stored control value
  W,    // action on writing 1; reads as the status its meaning names (often 0)
  W1C,  // latched status: set by the chip, cleared by writing 1
};

// Where a field's definition comes from (brief: decisions are written down).
enum class Source : std::uint8_t {
  Datasheet,  // sercon816-datasheet.txt
  DeltaSpec,  // sercon816-delta-spec-en.txt
  Facts,      // sercos-facts.md (seen or inferred from real drivers)
  Project,    // decided by the project where the sources are silent (docs/registers.md)
};

// Which variants have a field; 410B-compatible mode of the 816 counts as the 816 here
// (it changes bit rates and clocks, not the register layout).
enum class Variants : std::uint8_t { Both, Only816, Only410B };

struct BitField {
  std::string_view name;
  std::uint8_t lsb;
  std::uint8_t width;
  Access access;
  std::uint16_t reset;  // field value after any reset, before pins (see reset_value())
  Variants variants;
  Source source;
  std::string_view meaning;

  constexpr std::uint16_t mask() const {
    return static_cast<std::uint16_t>(((1u << width) - 1u) << lsb);
  }
};

struct RegisterInfo {
  std::uint8_t address;
  std::string_view name;
  std::span<const BitField> fields;  // ascending lsb; bits not named read 0
};

// Every register 0x00..0x2A, in address order (index == address).
std::span<const RegisterInfo> register_map();
const RegisterInfo& register_info(std::uint8_t address);  // address must be < kRegisterCount
// Fields present in `variant`, looked up by name (nullopt when absent in that variant).
std::optional<BitField> find_field(std::string_view name, Variant variant);

// Bit masks for one register in one variant, derived from the table.
struct RegisterMasks {
  std::uint16_t readable;   // bits that read back a value (others read 0)
  std::uint16_t writable;   // RW bits
  std::uint16_t action;     // W bits
  std::uint16_t clearable;  // W1C bits
  std::uint16_t reset;      // value after reset (pin-dependent bits: see Chip)
};
RegisterMasks register_masks(std::uint8_t address, Variant variant);

}  // namespace sercon::chip

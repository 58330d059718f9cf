// A signal declared in a VCD header ($var), and how `--signal` picks one of them.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace sercon::capture {

struct VcdVariable {
  std::string type;  // wire, reg, integer, real, event, ...
  std::uint32_t width = 0;
  std::string id;         // identifier code used in value changes
  std::string reference;  // declared name, without any bit select
  std::string scope;      // enclosing scopes joined by '.', empty at the top

  // scope.reference, or just the reference at the top level.
  std::string full_name() const;
  // A 1-bit signal that carries line levels (not a real, event or string).
  bool is_line_candidate() const;
};

// Picks the signal to decode. `wanted` matches a reference or a full hierarchical name;
// empty means "the only 1-bit signal". Throws CaptureError naming the candidates when
// nothing or more than one signal fits, or when the named signal is not 1 bit wide.
const VcdVariable& select_vcd_variable(const std::vector<VcdVariable>& variables,
                                       std::string_view wanted);

}  // namespace sercon::capture

// The two chips this model can be: the SERCON816 and its predecessor SERCON410B.
#pragma once

#include <cstdint>
#include <string_view>

namespace sercon::chip {

enum class Variant : std::uint8_t { Sercon816, Sercon410B };

constexpr std::string_view to_string(Variant v) {
  return v == Variant::Sercon816 ? "SERCON816" : "SERCON410B";
}
// Delta spec 2.11.1.1: VERSION register values.
constexpr std::uint16_t version_of(Variant v) { return v == Variant::Sercon816 ? 0x0010 : 0x0002; }
// Delta spec 2.5: 2K words on the 816, 1K on the 410B.
constexpr std::uint16_t ram_words_of(Variant v) { return v == Variant::Sercon816 ? 2048 : 1024; }

}  // namespace sercon::chip

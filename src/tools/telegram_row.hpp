// One line of `sercon decode` output: a telegram, or a frame with an error, in the words
// the text and JSON outputs print.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string_view>
#include <vector>

namespace sercon::tools {

// Kinds of telegram (docs/decode.md): the line tells only address and length.
enum class TelegramKind : std::uint8_t {
  Mst,        // address 255, one data byte
  Mdt,        // address 255, any other length
  At,         // address 1..254 outside CP1/CP2
  AtOrMdt,    // address 1..254 in CP1/CP2: a drive's AT or the single-drive MDT
  NoStation,  // address 0, "no station" (sercos-facts §1)
};
inline constexpr std::size_t kTelegramKindCount = 5;

// Frame errors as decode reports them (the wire decoder's classes).
enum class ErrorClass : std::uint8_t { BadFcs, Abort, TooShort, Misaligned, Truncated };
inline constexpr std::size_t kErrorClassCount = 5;

std::string_view kind_name(TelegramKind kind);       // "MST", "AT/MDT", "ADDR0", ...
std::string_view error_json_name(ErrorClass error);  // "bad_fcs", "too_short", ...
std::string_view error_text_name(ErrorClass error);  // "bad-fcs", "too-short", ...

struct TelegramRow {
  std::int64_t t_ps = 0;      // first bit of the opening flag, from the capture start
  std::size_t start_bit = 0;  // line bit index of the same
  std::size_t end_bit = 0;    // one past the closing flag, or where the error was found
  // Unset for frames that are not whole telegrams (errors other than bad FCS).
  std::optional<TelegramKind> kind;
  std::uint8_t address = 0;
  std::vector<std::uint8_t> data;  // after the address; for errors other than bad FCS,
                                   // every whole byte received (FCS included)
  std::optional<bool> fcs_ok;      // unset when the frame has no recognisable FCS
  std::uint16_t fcs_received = 0;
  std::uint16_t fcs_computed = 0;
  std::optional<unsigned> phase;  // MSTs: low 3 bits of the data byte
  std::optional<ErrorClass> error;

  bool phase_valid() const { return phase && *phase <= 4; }
};

}  // namespace sercon::tools

// Names what each decoded frame is. The line shows only address and length, so the kind of
// an addressed telegram depends on the phase announced by the last good MST
// (sercos-facts §2): in CP1/CP2 it may be a drive's AT or the master's single-drive MDT.
#pragma once

#include <cstdint>
#include <optional>

#include "sercon/wire/decoder.hpp"
#include "telegram_row.hpp"

namespace sercon::tools {

class TelegramClassifier {
 public:
  // `t_ps`: the frame's start from the capture start. Only MSTs with a good FCS change
  // the phase.
  TelegramRow classify(const wire::DecodedFrame& frame, std::int64_t t_ps);

  // The phase of the last good MST (low 3 bits of its data byte), if any yet.
  std::optional<unsigned> phase() const { return phase_; }

 private:
  TelegramKind kind_of(std::uint8_t address, std::size_t length) const;

  std::optional<unsigned> phase_;
};

}  // namespace sercon::tools

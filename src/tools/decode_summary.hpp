// What a whole decode saw: telegrams by kind, errors by class, the phases in the order
// the MSTs announced them.
#pragma once

#include <array>
#include <cstddef>
#include <vector>

#include "telegram_row.hpp"

namespace sercon::tools {

class DecodeSummary {
 public:
  void add(const TelegramRow& row);

  // Telegrams without error (a bad-FCS frame counts as an error, not a telegram).
  std::size_t telegrams() const { return telegrams_; }
  std::size_t telegrams(TelegramKind kind) const {
    return by_kind_[static_cast<std::size_t>(kind)];
  }
  std::size_t errors() const { return errors_; }
  std::size_t errors(ErrorClass error) const { return by_error_[static_cast<std::size_t>(error)]; }
  // Phases of good MSTs, a repeat of the previous phase left out: {0, 1, 2, 3, 4}.
  const std::vector<unsigned>& phases() const { return phases_; }
  std::size_t invalid_phase_msts() const { return invalid_phase_msts_; }

 private:
  std::size_t telegrams_ = 0;
  std::size_t errors_ = 0;
  std::array<std::size_t, kTelegramKindCount> by_kind_{};
  std::array<std::size_t, kErrorClassCount> by_error_{};
  std::vector<unsigned> phases_;
  std::size_t invalid_phase_msts_ = 0;
};

inline constexpr std::array<TelegramKind, kTelegramKindCount> kAllKinds{
    TelegramKind::Mst, TelegramKind::Mdt, TelegramKind::At, TelegramKind::AtOrMdt,
    TelegramKind::NoStation};
inline constexpr std::array<ErrorClass, kErrorClassCount> kAllErrors{
    ErrorClass::BadFcs, ErrorClass::Abort, ErrorClass::TooShort, ErrorClass::Misaligned,
    ErrorClass::Truncated};

}  // namespace sercon::tools

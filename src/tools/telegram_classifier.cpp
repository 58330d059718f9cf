#include "telegram_classifier.hpp"

namespace sercon::tools {
namespace {

constexpr std::uint8_t kBroadcast = 255;
constexpr std::uint8_t kNoStation = 0;

std::optional<ErrorClass> error_class(wire::FrameError error) {
  switch (error) {
    case wire::FrameError::None:
      return std::nullopt;
    case wire::FrameError::BadFcs:
      return ErrorClass::BadFcs;
    case wire::FrameError::Abort:
      return ErrorClass::Abort;
    case wire::FrameError::TooShort:
      return ErrorClass::TooShort;
    case wire::FrameError::Misaligned:
      return ErrorClass::Misaligned;
    case wire::FrameError::Truncated:
      return ErrorClass::Truncated;
  }
  return std::nullopt;
}

}  // namespace

TelegramKind TelegramClassifier::kind_of(std::uint8_t address, std::size_t length) const {
  if (address == kBroadcast) return length == 1 ? TelegramKind::Mst : TelegramKind::Mdt;
  if (address == kNoStation) return TelegramKind::NoStation;
  const bool single_drive_mdt_possible = phase_ && (*phase_ == 1 || *phase_ == 2);
  return single_drive_mdt_possible ? TelegramKind::AtOrMdt : TelegramKind::At;
}

TelegramRow TelegramClassifier::classify(const wire::DecodedFrame& frame, std::int64_t t_ps) {
  TelegramRow row;
  row.t_ps = t_ps;
  row.start_bit = frame.start_bit;
  row.end_bit = frame.end_bit;
  row.address = frame.address;
  row.data = frame.data;
  row.error = error_class(frame.error);

  const bool whole_telegram =
      frame.error == wire::FrameError::None || frame.error == wire::FrameError::BadFcs;
  if (!whole_telegram) return row;

  row.kind = kind_of(frame.address, frame.data.size());
  row.fcs_ok = frame.error == wire::FrameError::None;
  row.fcs_received = frame.fcs_received;
  row.fcs_computed = frame.fcs_computed;
  if (*row.kind == TelegramKind::Mst) {
    row.phase = frame.data.front() & 0x07U;
    if (*row.fcs_ok) phase_ = row.phase;
  }
  return row;
}

}  // namespace sercon::tools

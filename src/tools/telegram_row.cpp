#include "telegram_row.hpp"

namespace sercon::tools {

std::string_view kind_name(TelegramKind kind) {
  switch (kind) {
    case TelegramKind::Mst:
      return "MST";
    case TelegramKind::Mdt:
      return "MDT";
    case TelegramKind::At:
      return "AT";
    case TelegramKind::AtOrMdt:
      return "AT/MDT";
    case TelegramKind::NoStation:
      return "ADDR0";
  }
  return "?";
}

std::string_view error_json_name(ErrorClass error) {
  switch (error) {
    case ErrorClass::BadFcs:
      return "bad_fcs";
    case ErrorClass::Abort:
      return "abort";
    case ErrorClass::TooShort:
      return "too_short";
    case ErrorClass::Misaligned:
      return "misaligned";
    case ErrorClass::Truncated:
      return "truncated";
  }
  return "?";
}

std::string_view error_text_name(ErrorClass error) {
  switch (error) {
    case ErrorClass::BadFcs:
      return "bad-fcs";
    case ErrorClass::Abort:
      return "abort";
    case ErrorClass::TooShort:
      return "too-short";
    case ErrorClass::Misaligned:
      return "misaligned";
    case ErrorClass::Truncated:
      return "truncated";
  }
  return "?";
}

}  // namespace sercon::tools

#include "json_output.hpp"

#include <string>

#include "bit_rate.hpp"
#include "hex.hpp"

namespace sercon::tools {
namespace {

// Whole nanoseconds as an integer, otherwise a fraction exact to the picosecond.
nlohmann::ordered_json nanoseconds(std::int64_t ps) {
  if (ps % 1000 == 0) return ps / 1000;
  return static_cast<double>(ps) / 1000.0;
}

}  // namespace

nlohmann::ordered_json json_row(const TelegramRow& row) {
  nlohmann::ordered_json j;
  j["t_ns"] = nanoseconds(row.t_ps);
  if (row.error) j["error"] = error_json_name(*row.error);
  if (row.kind) j["kind"] = kind_name(*row.kind);
  j["address"] = row.address;
  j["length"] = row.data.size();
  j["data"] = to_hex(row.data);
  if (row.fcs_ok) j["fcs_ok"] = *row.fcs_ok;
  if (row.error == ErrorClass::BadFcs) {
    j["fcs_received"] = to_hex16(row.fcs_received);
    j["fcs_computed"] = to_hex16(row.fcs_computed);
  }
  if (row.phase) {
    j["phase"] = *row.phase;
    j["phase_valid"] = row.phase_valid();
  }
  j["start_bit"] = row.start_bit;
  j["end_bit"] = row.end_bit;
  return j;
}

nlohmann::ordered_json json_summary(const DecodeSummary& summary, const DecodeRunInfo& info) {
  nlohmann::ordered_json kinds = nlohmann::ordered_json::object();
  for (TelegramKind kind : kAllKinds) kinds[std::string(kind_name(kind))] = summary.telegrams(kind);
  nlohmann::ordered_json errors = nlohmann::ordered_json::object();
  for (ErrorClass error : kAllErrors) {
    errors[std::string(error_json_name(error))] = summary.errors(error);
  }

  nlohmann::ordered_json s;
  s["telegrams"] = summary.telegrams();
  s["kinds"] = kinds;
  s["error_count"] = summary.errors();
  s["errors"] = errors;
  s["fcs_errors"] = summary.errors(ErrorClass::BadFcs);
  s["phases"] = summary.phases();
  s["bit_rate"] = bits_per_second(info.bit_period_ps);
  s["bit_period_ps"] = info.bit_period_ps;
  s["rate_source"] = info.rate_given ? "option" : "detected";
  s["format"] = capture::format_name(info.format);
  if (!info.signal.empty()) s["signal"] = info.signal;
  s["line_bits"] = info.line_bits;
  if (info.unknown_values > 0) s["unknown_values"] = info.unknown_values;
  nlohmann::ordered_json out;
  out["summary"] = s;
  return out;
}

}  // namespace sercon::tools

#include "text_output.hpp"

#include <fmt/format.h>

#include "bit_rate.hpp"
#include "hex.hpp"

namespace sercon::tools {

std::string rate_text(const DecodeRunInfo& info) {
  return describe_bit_period(info.bit_period_ps) +
         (info.rate_given ? " (from --rate)" : " (detected from the capture)");
}

std::string text_header(const DecodeRunInfo& info) {
  std::string source = std::string(capture::format_name(info.format));
  if (!info.signal.empty()) source += ", signal " + info.signal;
  return fmt::format("# sercon decode {}: {}, {}\n# {:>10}  {:<6}  {:>4}  {:>4}  fields\n",
                     info.file, source, rate_text(info), "t_ns", "kind", "addr", "len");
}

std::string text_row(const TelegramRow& row) {
  const std::string kind = row.kind ? std::string(kind_name(*row.kind)) : "-";
  std::string line =
      fmt::format("{:>12.1f}  {:<6}  {:>4}  {:>4}  data={}", static_cast<double>(row.t_ps) / 1000.0,
                  kind, row.address, row.data.size(), to_hex(row.data));
  if (row.fcs_ok) line += *row.fcs_ok ? " fcs=ok" : " fcs=bad";
  if (row.phase) {
    line += fmt::format(" phase={}", *row.phase);
    if (!row.phase_valid()) line += " (invalid: above 4)";
  }
  if (row.error) {
    line += fmt::format(" error={}", error_text_name(*row.error));
    if (*row.error == ErrorClass::BadFcs) {
      line += fmt::format(" fcs_received={} fcs_computed={}", to_hex16(row.fcs_received),
                          to_hex16(row.fcs_computed));
    }
  }
  return line;
}

std::string text_summary(const DecodeSummary& summary, const DecodeRunInfo& info) {
  std::string kinds;
  for (TelegramKind kind : kAllKinds) {
    if (summary.telegrams(kind) == 0) continue;
    kinds +=
        fmt::format("{}{} {}", kinds.empty() ? "" : ", ", kind_name(kind), summary.telegrams(kind));
  }
  std::string errors;
  for (ErrorClass error : kAllErrors) {
    if (summary.errors(error) == 0) continue;
    errors += fmt::format("{}{} {}", errors.empty() ? "" : ", ", error_text_name(error),
                          summary.errors(error));
  }
  // A long capture may fall back and phase up many times: show the start and the end.
  const std::vector<unsigned>& seen = summary.phases();
  constexpr std::size_t kHead = 16;
  constexpr std::size_t kTail = 8;
  std::string phases;
  for (std::size_t i = 0; i < seen.size(); ++i) {
    if (seen.size() > kHead + kTail && i == kHead) {
      phases += fmt::format(" -> ... ({} phases in all)", seen.size());
      i = seen.size() - kTail;
    }
    phases += fmt::format("{}{}{}", i == 0 ? "" : " -> ", seen[i], seen[i] > 4 ? " (invalid)" : "");
  }

  std::string out = "summary\n";
  out += fmt::format("  telegrams  {}{}\n", summary.telegrams(),
                     kinds.empty() ? "" : " (" + kinds + ")");
  out += fmt::format("  errors     {}{}\n", summary.errors(),
                     errors.empty() ? "" : " (" + errors + ")");
  out += fmt::format("  phases     {}\n", phases.empty() ? "none (no MST)" : phases);
  out += fmt::format("  bit rate   {}\n", rate_text(info));
  out += fmt::format("  line bits  {}\n", info.line_bits);
  if (info.unknown_values > 0) {
    out += fmt::format("  x/z        {} x/z values on {} kept as no change\n", info.unknown_values,
                       info.signal);
  }
  if (summary.telegrams(TelegramKind::AtOrMdt) > 0) {
    out +=
        "  legend     AT/MDT = addressed telegram in CP1/CP2: the line alone cannot tell a "
        "drive's AT from the master's single-drive MDT (sercos-facts §2)\n";
  }
  if (summary.telegrams(TelegramKind::NoStation) > 0) {
    out +=
        "  legend     ADDR0 = address 0, \"no station\" (sercos-facts §1): no station sends it\n";
  }
  return out;
}

}  // namespace sercon::tools

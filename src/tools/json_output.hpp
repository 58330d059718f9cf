// The `--json` output of `sercon decode`: JSON Lines, one object per telegram or broken
// frame, the last line {"summary": {...}} (schema in docs/decode.md).
#pragma once

#include <nlohmann/json.hpp>

#include "decode_run_info.hpp"
#include "decode_summary.hpp"
#include "telegram_row.hpp"

namespace sercon::tools {

// ordered_json keeps the keys in schema order, so t_ns leads every line.
nlohmann::ordered_json json_row(const TelegramRow& row);
nlohmann::ordered_json json_summary(const DecodeSummary& summary, const DecodeRunInfo& info);

}  // namespace sercon::tools

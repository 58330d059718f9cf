// The human-readable output of `sercon decode`: a header, one line per telegram or broken
// frame, then the summary (columns described in docs/decode.md).
#pragma once

#include <string>

#include "decode_run_info.hpp"
#include "decode_summary.hpp"
#include "telegram_row.hpp"

namespace sercon::tools {

std::string text_header(const DecodeRunInfo& info);  // ends with a newline
std::string text_row(const TelegramRow& row);        // one line, no newline
std::string text_summary(const DecodeSummary& summary, const DecodeRunInfo& info);

// "4 Mbit/s (from --rate)" / "4 Mbit/s (detected from the capture)".
std::string rate_text(const DecodeRunInfo& info);

}  // namespace sercon::tools

// The four SERCOS II bit rates (sercos-facts §1) as `--rate` names them.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

namespace sercon::tools {

// "2M", "4M", "8M", "16M" (M or m, optionally "bit/s" or "bps" after it; or the plain
// number of bit/s) -> the bit period in ps. Throws InputError for any other rate.
std::int64_t parse_bit_rate(std::string_view text);

// 250'000 -> "4 Mbit/s"; a period that is no SERCOS rate prints as "N ps bits".
std::string describe_bit_period(std::int64_t period_ps);

// 250'000 -> 4'000'000.
std::int64_t bits_per_second(std::int64_t period_ps);

}  // namespace sercon::tools

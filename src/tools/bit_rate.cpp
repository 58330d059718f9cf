#include "bit_rate.hpp"

#include <array>
#include <cctype>

#include "input_error.hpp"

namespace sercon::tools {
namespace {

struct Rate {
  std::string_view name;
  std::int64_t mbit;
  std::int64_t period_ps;
};
constexpr std::array<Rate, 4> kRates{{
    {"2M", 2, 500'000},
    {"4M", 4, 250'000},
    {"8M", 8, 125'000},
    {"16M", 16, 62'500},
}};

std::string lower(std::string_view text) {
  std::string out;
  for (char c : text) out += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

}  // namespace

std::int64_t parse_bit_rate(std::string_view text) {
  std::string s = lower(text);
  for (std::string_view suffix : {"bit/s", "bps"}) {
    if (s.size() > suffix.size() && s.ends_with(suffix)) s.resize(s.size() - suffix.size());
  }
  for (const Rate& rate : kRates) {
    const std::string mbit = std::to_string(rate.mbit);
    if (s == mbit + "m" || s == mbit + "000000") return rate.period_ps;
  }
  throw InputError("impossible bit rate '" + std::string(text) +
                   "': SERCOS II runs at 2M, 4M, 8M or 16M (bit/s)");
}

std::string describe_bit_period(std::int64_t period_ps) {
  for (const Rate& rate : kRates) {
    if (rate.period_ps == period_ps) return std::to_string(rate.mbit) + " Mbit/s";
  }
  return std::to_string(period_ps) + " ps bits";
}

std::int64_t bits_per_second(std::int64_t period_ps) {
  return period_ps > 0 ? 1'000'000'000'000 / period_ps : 0;
}

}  // namespace sercon::tools

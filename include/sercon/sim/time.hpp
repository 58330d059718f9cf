// Simulated time: an integer count of picoseconds, so that 62.5 ns bit times and
// 15.625 ns MCLK periods are exact.
#pragma once

#include <cstdint>

namespace sercon::sim {

using Time = std::int64_t;  // picoseconds since the simulation started

inline constexpr Time kPicosecond = 1;
inline constexpr Time kNanosecond = 1'000;
inline constexpr Time kMicrosecond = 1'000'000;
inline constexpr Time kMillisecond = 1'000'000'000;
inline constexpr Time kSecond = 1'000'000'000'000;

// Period of a clock of `hz` Hz in picoseconds; exact for every clock the chip accepts
// (12..64 MHz MCLK, 64 MHz SCLK, 2/4/8/16 Mbit/s) as long as 1e12 is divisible by hz.
constexpr Time period_of_hz(std::int64_t hz) { return kSecond / hz; }

}  // namespace sercon::sim

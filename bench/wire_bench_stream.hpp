// The benchmark workload shared by the wire benchmarks: a long SERCOS telegram stream of
// the realistic mix (sercos-facts §2) — per cycle an MST of 1 byte, four 8-byte ATs and a
// 32-byte MDT, random data, 8..72 bits of fill between telegrams.
#pragma once

#include <cstdint>
#include <random>
#include <vector>

#include "sercon/wire/telegram.hpp"

namespace sercon::wire::bench {

struct StreamItem {
  Telegram telegram;
  std::size_t idle_after = 0;
};

inline std::vector<StreamItem> make_stream(int cycles, std::uint64_t seed = 42) {
  std::mt19937_64 rng(seed);
  std::vector<StreamItem> items;
  auto add = [&](std::uint8_t address, std::size_t size) {
    StreamItem it;
    it.telegram.address = address;
    it.telegram.data.resize(size);
    for (auto& b : it.telegram.data) b = static_cast<std::uint8_t>(rng());
    it.idle_after = 8 + rng() % 65;
    items.push_back(std::move(it));
  };
  for (int c = 0; c < cycles; ++c) {
    add(0xFF, 1);
    for (std::uint8_t drive = 1; drive <= 4; ++drive) add(drive, 8);
    add(0xFF, 32);
  }
  return items;
}

}  // namespace sercon::wire::bench

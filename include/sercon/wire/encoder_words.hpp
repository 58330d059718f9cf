// The word coder behind wire::encode_telegram (encoder.hpp), in a header so that the chip's
// transmitter (chip/line_decode_memo.cpp, encode_seeded) has it inlined: a call per
// telegram, its arguments and its result through memory, were a measurable share of an
// own telegram. Not an interface: use encode_telegram or LineEncoder.
#pragma once

#include <array>
#include <bit>
#include <cassert>
#include <cstdint>
#include <cstring>
#include <span>

#include "sercon/wire/encoder.hpp"
#include "sercon/wire/fcs.hpp"
#include "sercon/wire/line_bits.hpp"

namespace sercon::wire::encoder_detail {

// Entry for (run of 1s before the byte, byte): the stuffed bits in time order, right
// aligned with the first bit highest (bits 0..9), their count (bits 10..13) and the run
// after the byte (bits 14..16). A byte yields at most 10 bits (run 4, byte 0xFF).
constexpr std::array<std::uint32_t, 5 * 256> make_stuff_table() {
  std::array<std::uint32_t, 5 * 256> table{};
  for (unsigned run0 = 0; run0 < 5; ++run0) {
    for (unsigned byte = 0; byte < 256; ++byte) {
      unsigned run = run0;
      std::uint32_t out = 0;
      unsigned count = 0;
      for (unsigned i = 0; i < 8; ++i) {  // LSB first on the line (sercos-facts §1)
        const unsigned bit = (byte >> i) & 1u;
        out = (out << 1) | bit;
        ++count;
        run = bit ? run + 1 : 0;
        if (run == 5) {  // five 1s: insert a 0 (sercos-facts §1)
          out <<= 1;
          ++count;
          run = 0;
        }
      }
      table[run0 * 256 + byte] = out | (count << 10) | (run << 14);
    }
  }
  return table;
}

inline constexpr std::array<std::uint32_t, 5 * 256> kStuff = make_stuff_table();

inline constexpr std::uint64_t kOnes = ~std::uint64_t{0};
inline constexpr std::uint64_t kIdlePattern = 0x7F7F7F7F7F7F7F7Full;  // `0 1111111`, MSB first

inline std::uint64_t top_mask(unsigned n) { return n == 0 ? 0 : kOnes << (64 - n); }

// NRZI (sercos-facts §1): a 0 is a level change. Prefix XOR from the MSB turns the changes
// into "odd number of changes so far", i.e. the level relative to the level before.
inline std::uint64_t changes_so_far(std::uint64_t changes) {
  changes ^= changes >> 1;
  changes ^= changes >> 2;
  changes ^= changes >> 4;
  changes ^= changes >> 8;
  changes ^= changes >> 16;
  changes ^= changes >> 32;
  return changes;
}

// Decoded bits on their way to NRZI. The hot paths keep them in a local so they stay in
// registers: the encoder's members would go to memory around every byte read (a uint8_t
// may alias them), and handing them between functions through memory measured slower.
struct Decoded {
  std::uint64_t bits = 0;  // MSB first
  unsigned count = 0;      // < 64 between calls
  unsigned run = 0;        // consecutive 1s for the stuffing rule
};

// Appends the `n` (0..64) low bits of msb_first, first bit highest; a full word goes to
// `full` (NRZI onto the line).
template <class Full>
[[gnu::always_inline]] inline void put(Decoded& d, std::uint64_t msb_first, unsigned n,
                                       const Full& full) {
  assert(d.count < 64 && n <= 64);             // checked in debug builds: the hint below
  if (d.count >= 64) __builtin_unreachable();  // as put_top
  const unsigned room = 64 - d.count;
  if (n < room) {
    d.bits |= msb_first << (room - n);
    d.count += n;
    return;
  }
  const unsigned rest = n - room;  // bits that do not fit in this word
  full(d.bits | msb_first >> rest);
  d.bits = rest == 0 ? 0 : msb_first << (64 - rest);
  d.count = rest;
}

// Inlined, so that `d` stays a caller's local (see Decoded).
template <class Full>
[[gnu::always_inline]] inline void stuff_into(Decoded& d, std::span<const std::uint8_t> bytes,
                                              const Full& full) {
  for (std::uint8_t b : bytes) {
    const std::uint32_t e = kStuff[d.run * 256 + b];
    put(d, e & 0x3FFu, (e >> 10) & 0xFu, full);
    d.run = e >> 14;
  }
}

// The `n` (0..8) bytes at `p` as one word, the first byte lowest: their line order (LSB
// first) from bit 0 up. Never reads past them.
inline std::uint64_t load_le(const std::uint8_t* p, std::size_t n) {
  const auto get32 = [](const std::uint8_t* q) {
    std::uint32_t v;
    std::memcpy(&v, q, 4);
    if constexpr (std::endian::native == std::endian::big) v = __builtin_bswap32(v);
    return std::uint64_t{v};
  };
  if (n >= 4) return get32(p) | get32(p + n - 4) << (8 * (n - 4));  // overlapping halves
  if (n == 0) return 0;
  return std::uint64_t{p[0]} | std::uint64_t{p[n / 2]} << (8 * (n / 2)) |
         std::uint64_t{p[n - 1]} << (8 * (n - 1));
}

inline std::uint64_t load_le8(const std::uint8_t* p) {
  std::uint64_t v;
  std::memcpy(&v, p, 8);
  if constexpr (std::endian::native == std::endian::big) v = __builtin_bswap64(v);
  return v;
}

// Bit i to bit 63 - i: line order from the first bit highest.
inline std::uint64_t reverse_bits(std::uint64_t x) {
  x = __builtin_bswap64(x);
  x = (x >> 4 & 0x0F0F0F0F0F0F0F0Full) | (x & 0x0F0F0F0F0F0F0F0Full) << 4;
  x = (x >> 2 & 0x3333333333333333ull) | (x & 0x3333333333333333ull) << 2;
  return (x >> 1 & 0x5555555555555555ull) | (x & 0x5555555555555555ull) << 1;
}

// Bit i set where bits i..i-4 of `x` (i down, first bit highest) are all 1.
inline std::uint64_t five_ones(std::uint64_t x) {
  const std::uint64_t two = x & x << 1;
  return two & two << 2 & x << 4;
}

// Appends the top `n` (1..64) bits of `top` (the rest 0), first bit highest.
template <class Full>
[[gnu::always_inline]] inline void put_top(Decoded& d, std::uint64_t top, unsigned n,
                                           const Full& full) {
  // Told, so that a whole word's put (n = 64, the word loop) has no test of its size.
  assert(d.count < 64 && n <= 64);
  if (d.count >= 64) __builtin_unreachable();
  d.bits |= top >> d.count;
  const unsigned total = d.count + n;
  if (total < 64) {
    d.count = total;
    return;
  }
  full(d.bits);
  d.bits = d.count == 0 ? 0 : top << (64 - d.count);
  d.count = total - 64;
}

// Up to this many bytes are stuffed a byte at a time (a telegram's FCS alone, mostly).
inline constexpr unsigned kTableBytes = 3;

// `bytes` (1..8 bytes, the first lowest) stuffed at once when no five 1s come together in
// them, with the run carried in (most data has no such run); else byte by byte.
template <class Full>
[[gnu::always_inline]] inline void stuff_word(Decoded& d, std::uint64_t bytes, unsigned n,
                                              const Full& full) {
  if (n <= kTableBytes) {  // a lookup a byte is cheaper than the word's tests
    for (unsigned i = 0; i < n; ++i, bytes >>= 8) {
      const std::uint32_t e = kStuff[d.run * 256 + (bytes & 0xFFu)];
      put(d, e & 0x3FFu, (e >> 10) & 0xFu, full);
      d.run = e >> 14;
    }
    return;
  }
  const unsigned bits = 8 * n;
  const std::uint64_t top = reverse_bits(bytes);  // the rest 0: no run reaches past them
  if (five_ones(top) == 0 && d.run + static_cast<unsigned>(std::countl_one(top)) < 5) [[likely]] {
    put_top(d, top, bits, full);
    d.run = static_cast<unsigned>(std::countr_one(top >> (64 - bits)));
    return;
  }
  // Five 1s (the run carried in counted): a 0 goes in after them, found one at a time from
  // the first bit; the bits between go as they are.
  std::uint64_t rest = top;  // bits still to go, first highest, the rest 0
  unsigned left = bits;
  unsigned run = d.run;
  for (;;) {
    unsigned take;  // bits up to the fifth 1
    if (run + static_cast<unsigned>(std::countl_one(rest)) >= 5) {
      take = 5 - run;
    } else {
      const std::uint64_t five = five_ones(rest);
      if (five == 0) break;
      take = static_cast<unsigned>(std::countl_zero(five)) + 5;  // a run of five starts there
    }
    put_top(d, rest & top_mask(take), take, full);
    if (++d.count == 64) {  // the stuffed 0: the bit is 0 already
      full(d.bits);
      d.bits = 0;
      d.count = 0;
    }
    rest = take < 64 ? rest << take : 0;
    left -= take;
    run = 0;
  }
  if (left == 0) {
    d.run = run;
    return;
  }
  put_top(d, rest, left, full);
  const auto ones = static_cast<unsigned>(std::countr_one(rest >> (64 - left)));
  d.run = ones == left ? run + ones : ones;
}

// Address, data and FCS (low byte first) stuffed into `d` (each full word to `full`); the
// FCS is worked out on the way, on the words as they are stuffed (one load each), and
// returned.
template <class Full>
[[gnu::always_inline]] inline std::uint16_t stuff_telegram(Decoded& d, std::uint8_t address,
                                                           std::span<const std::uint8_t> data,
                                                           const Full& full) {
  const std::uint8_t* p = data.data();
  std::size_t n = data.size();
  Fcs16 fcs;
  // The address by the table (255, an MST's or MDT's, has five 1s, which would send a word
  // the slow way), then the data 8 bytes at a time, the last 6 or fewer with the FCS.
  const std::uint32_t e = kStuff[d.run * 256 + address];
  put(d, e & 0x3FFu, (e >> 10) & 0xFu, full);
  d.run = e >> 14;
  if (n <= 6) {  // a short telegram (an AT, an MST): one FCS update for address and data
    const std::uint64_t tail = load_le(p, n);
    fcs.update_word(address | tail << 8, static_cast<unsigned>(n + 1));
    const std::uint16_t v = fcs.value();
    stuff_word(d, tail | std::uint64_t{v} << (8 * n), static_cast<unsigned>(n + 2), full);
    return v;
  }
  fcs.update_word(address, 1);
  // Whole words with the sizes known (a word's bits fill the coder's word exactly: no
  // tests of them); of 7 left, one byte by the table, so that the tail takes the rest.
  for (; n >= 8; p += 8, n -= 8) {
    const std::uint64_t w = load_le8(p);
    fcs.update_word(w, 8);
    stuff_word(d, w, 8, full);
  }
  if (n == 7) {
    const std::uint64_t b = *p++;
    fcs.update_word(b, 1);
    stuff_word(d, b, 1, full);
    n = 6;
  }
  const std::uint64_t tail = load_le(p, n);
  if (n != 0) fcs.update_word(tail, static_cast<unsigned>(n));
  const std::uint16_t v = fcs.value();
  stuff_word(d, tail | std::uint64_t{v} << (8 * n), static_cast<unsigned>(n + 2), full);
  return v;
}

// Flag, address, data, FCS (low byte first), flag as decoded bits into `d`, each full word
// to `full`; returns the FCS.
template <class Full>
[[gnu::always_inline]] inline std::uint16_t code_telegram(Decoded& d, std::uint8_t address,
                                                          std::span<const std::uint8_t> data,
                                                          const Full& full) {
  put(d, 0x7E, 8, full);  // flag; the stuffing count starts after it
  d.run = 0;
  const std::uint16_t v = stuff_telegram(d, address, data, full);
  put(d, 0x7E, 8, full);
  return v;
}

// encode_telegram, inlined.
[[gnu::always_inline]] inline TelegramCoding encode_telegram_inline(
    LineBits& out, bool initial_level_high, std::uint8_t address,
    std::span<const std::uint8_t> data) {
  // Every byte of flags, address, data and FCS is written again, as whole words from bit 0
  // (so the bytes of 8 * (size + 5) bits rounded up to a word): of the old bits, only bytes
  // past those are cleared.
  out.drop_for_overwrite((data.size() + 5 + 7) & ~std::size_t{7});
  // One allocation for all of it (flags and at most 10 bits per stuffed byte, and a word of
  // room past them), every word stored at a byte boundary into it (reserved_bytes).
  out.reserve(16 + 10 * (data.size() + 3) + 64);
  std::uint8_t* const first = out.reserved_bytes();
  std::uint8_t* at = first;
  // NRZI as one XOR a word: changes_so_far(~w) is changes_so_far(w) ^ kAlternate (the
  // prefix XOR is linear, and of all 1s it alternates from 1 at the MSB), and the level
  // before the word flips it all when high. `flip` keeps both: kAlternate ^ (0 or all 1s).
  constexpr std::uint64_t kAlternate = 0xAAAAAAAAAAAAAAAAull;
  std::uint64_t flip = initial_level_high ? ~kAlternate : kAlternate;
  // Always inline: in a flattened caller (the chip's transmitter) GCC made it a call. GNU
  // spelling: [[gnu::always_inline]] before the parameters is C++23, which clang refuses.
  const auto full = [&at, &flip ](std::uint64_t w) __attribute__((always_inline)) {
    const std::uint64_t levels = changes_so_far(w) ^ flip;
    LineBits::store_word(at, levels);
    at += 8;
    flip = kAlternate ^ (0 - (levels & 1u));
  };
  Decoded d;
  const std::uint16_t fcs = code_telegram(d, address, data, full);
  std::size_t size = 8 * static_cast<std::size_t>(at - first);
  bool level = flip != kAlternate;
  if (d.count != 0) {
    // The bits past d.count (0) change nothing above them: they are masked off after.
    const std::uint64_t mask = kOnes << (64 - d.count);  // d.count is 1..63
    const std::uint64_t levels = (changes_so_far(d.bits) ^ flip) & mask;
    LineBits::store_word(at, levels);  // the rest 0
    level = ((levels >> (64 - d.count)) & 1u) != 0;
    size += d.count;
  }
  out.written(size);
  return {{0, size}, level, fcs};
}

}  // namespace sercon::wire::encoder_detail

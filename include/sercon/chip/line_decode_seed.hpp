// The transmitter's own telegram coded with its decode (encode_seeded), in a header so that
// SerialTransmitter::send, its one caller, has it inlined (send is flattened): the call per
// telegram, its register saves and the bits handle through memory were a measurable share
// of an own telegram. And the seeded decode's fields (fill_seed, behind seed_decode too).
// The decode memo is line_decode_memo.hpp.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <memory>
#include <span>
#include <utility>
#include <vector>

#include "sercon/chip/line_decode_memo.hpp"
#include "sercon/chip/line_length.hpp"
#include "sercon/chip/shared_bits.hpp"
#include "sercon/wire/encoder_words.hpp"

namespace sercon::chip {
namespace seed_detail {

// Decodes made on this thread (burst_decode_count()). Constant-initialised, so that the
// coder finds it without a thread-local initialisation check.
extern thread_local constinit std::size_t decodes;

// Address + 1 data byte + 2 FCS bytes (decoder.hpp).
inline constexpr std::size_t kMinFrameBytes = 4;

// What the decoder finds in a burst that is one telegram as wire::LineEncoder::telegram()
// writes it, from the decoder's rules (wire/decoder.hpp): the opening flag opens a frame at
// its first bit, the closing flag closes it one past its last bit (and opens another that
// the burst's end leaves with no bits: no frame); the bits between are whole bytes,
// destuffed back to address, data and FCS. Four bytes or more with the right FCS: ok.
// Fewer (no data): TooShort, every byte after the address as data, both FCS fields 0
// (fill_seed below).

// The first and the last sizeof(Word) of n bytes (sizeof(Word) <= n <= 2 sizeof(Word)),
// each as one load and one store: together they cover all n.
template <class Word>
inline void move_head_and_tail(std::uint8_t* to, const std::uint8_t* from, std::size_t n) {
  Word head;
  Word tail;
  std::memcpy(&head, from, sizeof(Word));
  std::memcpy(&tail, from + n - sizeof(Word), sizeof(Word));
  std::memcpy(to, &head, sizeof(Word));
  std::memcpy(to + n - sizeof(Word), &tail, sizeof(Word));
}

// `to` made a copy of `from`, in the storage it has (a recycled decode, shared_bits.hpp): no
// library call for a telegram of up to 16 bytes unless `to` must grow.
[[gnu::always_inline]] inline void copy_bytes(std::vector<std::uint8_t>& to,
                                              std::span<const std::uint8_t> from) {
  const std::size_t n = from.size();
  if (n > to.size()) [[unlikely]] {
    if (n > to.capacity()) {
      to.assign(from.begin(), from.end());
      return;
    }
    to.resize(n);  // within its storage (it held a shorter telegram): cheaper than assign()
  } else {
    to.resize(n);  // no longer: nothing to fill
  }
  std::uint8_t* const t = to.data();
  const std::uint8_t* const f = from.data();
  // Head and tail moves, overlapping for sizes between the powers of two.
  if (n >= 8 && n <= 16) {
    move_head_and_tail<std::uint64_t>(t, f, n);
  } else if (n >= 4 && n < 8) {
    move_head_and_tail<std::uint32_t>(t, f, n);
  } else if (n > 0 && n < 4) {
    t[0] = f[0];
    t[n / 2] = f[n / 2];
    t[n - 1] = f[n - 1];
  } else if (n > 16) {
    std::memcpy(t, f, n);
  }
}

// Every field of `r` set to the one telegram's decode (seed_decode's rules above), its
// vectors' storage kept.
[[gnu::always_inline]] inline void fill_seed(BurstDecode& r, const wire::EncodedFrame& where,
                                             std::uint8_t address,
                                             std::span<const std::uint8_t> data,
                                             std::uint16_t fcs) {
  ++seed_detail::decodes;
  if (r.frames.size() != 1) r.frames.resize(1);
  wire::DecodedFrame& f = r.frames.front();
  f.start_bit = where.start_bit;
  f.end_bit = where.end_bit;
  f.address = address;
  if (data.size() + 3 >= seed_detail::kMinFrameBytes) [[likely]] {
    copy_bytes(f.data, data);
    f.fcs_received = fcs;
    f.fcs_computed = fcs;
    f.error = wire::FrameError::None;
  } else {
    f.data = {static_cast<std::uint8_t>(fcs & 0xFFu), static_cast<std::uint8_t>(fcs >> 8)};
    f.fcs_received = 0;
    f.fcs_computed = 0;
    f.error = wire::FrameError::TooShort;
  }
  const std::size_t address_end = where.start_bit + address_end_bit(address);
  if (r.address_end.size() == 1) {
    r.address_end.front() = address_end;
  } else {
    r.address_end.assign(1, address_end);
  }
  r.to_255 = address == kAddress255;
}

}  // namespace seed_detail

// One telegram as the transmitter sends it: a bits object of its own holding exactly the
// telegram's line bits, coded as wire::encode_telegram() codes them from line level
// `level` (the level after them on return), with seed_decode's decode. The object is a
// recycled one written over in place (shared_bits.hpp, rewrite_shared_bits): its old bits'
// bytes and its old decode's storage are set again, not cleared first (test
// serial_DecodeSeed.EncodeSeededIsTheGeneralPath).
inline SharedBits encode_seeded(bool& level, std::uint8_t address,
                                std::span<const std::uint8_t> data) {
  return rewrite_shared_bits([&](wire::LineBits& bits, BurstDecodes& d) {
    const wire::TelegramCoding c =
        wire::encoder_detail::encode_telegram_inline(bits, level, address, data);
    level = c.level_after;
    if (!d.prefixes.empty()) d.prefixes.clear();
    if (!d.whole) d.whole = d.spare ? std::move(d.spare) : std::make_unique<BurstDecode>();
    // Every decode is made non-const (run_decoder, seed_decode), so it may be filled again.
    seed_detail::fill_seed(const_cast<BurstDecode&>(*d.whole), c.frame, address, data, c.fcs);
  });
}

}  // namespace sercon::chip

#include "sercon/chip/line_decode_memo.hpp"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <memory>
#include <span>
#include <utility>

#include "sercon/chip/line_length.hpp"
#include "sercon/wire/encoder_words.hpp"

namespace sercon::chip {
namespace {

thread_local std::size_t decodes = 0;

constexpr std::size_t kMinFrameBytes = 4;  // address + 1 data byte + 2 FCS bytes (decoder.hpp)

// Feeds the lead-in level, then `count` bits of `bits`, then `dark_tail` bits without
// edges, and collects the frames with positions counted from the burst's first bit.
std::unique_ptr<const BurstDecode> run_decoder(const wire::LineBits& bits, std::size_t count,
                                               std::size_t dark_tail) {
  auto result = std::make_unique<BurstDecode>();
  ++decodes;
  if (count == 0) return result;
  result->frames.reserve(1);  // a burst is one telegram, but for collisions and cuts
  result->address_end.reserve(1);
  wire::LineDecoder decoder([&result](const wire::DecodedFrame& frame) {
    wire::DecodedFrame f = frame;
    f.start_bit -= 1;  // the lead-in bit
    f.end_bit -= 1;
    result->address_end.push_back(f.start_bit + address_end_bit(f.address));
    result->to_255 = result->to_255 || f.address == kAddress255;
    result->frames.push_back(std::move(f));
  });
  const std::uint8_t lead_in = bits.level(0) ? 0x00 : 0x80;  // the opposite level, MSB first
  decoder.feed(std::span<const std::uint8_t>(&lead_in, 1), 1);
  decoder.feed(bits.packed(), count);
  if (dark_tail > 0) {
    wire::LineBits tail;
    tail.append_run(bits.level(count - 1), dark_tail);
    decoder.feed(tail);
  }
  decoder.finish();
  return result;
}

}  // namespace

const BurstDecode& decode_whole_burst(const SharedBits& bits) {
  BurstDecodes& d = bits.decodes();
  // Only on a miss: receivers hold pointers to a decode made before.
  if (!d.whole) d.whole = run_decoder(*bits, bits->size(), 0);
  return *d.whole;
}

const BurstDecode& decode_burst_prefix(const SharedBits& bits, std::size_t cut_bit) {
  BurstDecodes& d = bits.decodes();
  for (const auto& [cut, decode] : d.prefixes) {
    if (cut == cut_bit) return *decode;
  }
  d.prefixes.emplace_back(cut_bit, run_decoder(*bits, std::min(cut_bit, bits->size()), 8));
  return *d.prefixes.back().second;
}

// What the decoder finds in a burst that is one telegram as wire::LineEncoder::telegram()
// writes it, from the decoder's rules (wire/decoder.hpp): the opening flag opens a frame at
// its first bit, the closing flag closes it one past its last bit (and opens another that
// the burst's end leaves with no bits: no frame); the bits between are whole bytes,
// destuffed back to address, data and FCS. Four bytes or more with the right FCS: ok.
// Fewer (no data): TooShort, every byte after the address as data, both FCS fields 0.
namespace {

// The first and the last sizeof(Word) of n bytes (sizeof(Word) <= n <= 2 sizeof(Word)),
// each as one load and one store: together they cover all n.
template <class Word>
void move_head_and_tail(std::uint8_t* to, const std::uint8_t* from, std::size_t n) {
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
  ++decodes;
  if (r.frames.size() != 1) r.frames.resize(1);
  wire::DecodedFrame& f = r.frames.front();
  f.start_bit = where.start_bit;
  f.end_bit = where.end_bit;
  f.address = address;
  if (data.size() + 3 >= kMinFrameBytes) [[likely]] {
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

}  // namespace

void seed_decode(const SharedBits& bits, const wire::EncodedFrame& where, std::uint8_t address,
                 std::span<const std::uint8_t> data, std::uint16_t fcs) {
  BurstDecodes& d = bits.decodes();
  if (d.whole || where.start_bit != 0 || where.end_bit != bits->size()) return;
  // A released object's decode, filled again (shared_bits.hpp, "Recycled"): every field
  // is set, the storage of its vectors kept.
  std::unique_ptr<BurstDecode> result =
      d.spare ? std::move(d.spare) : std::make_unique<BurstDecode>();
  fill_seed(*result, where, address, data, fcs);
  d.whole = std::move(result);
}

SharedBits encode_seeded(bool& level, std::uint8_t address, std::span<const std::uint8_t> data) {
  return rewrite_shared_bits([&](wire::LineBits& bits, BurstDecodes& d) {
    const wire::TelegramCoding c =
        wire::encoder_detail::encode_telegram_inline(bits, level, address, data);
    level = c.level_after;
    if (!d.prefixes.empty()) d.prefixes.clear();
    if (!d.whole) d.whole = d.spare ? std::move(d.spare) : std::make_unique<BurstDecode>();
    // Every decode is made non-const (run_decoder, seed_decode), so it may be filled again.
    fill_seed(const_cast<BurstDecode&>(*d.whole), c.frame, address, data, c.fcs);
  });
}

std::size_t burst_decode_count() { return decodes; }

}  // namespace sercon::chip

// Streaming line decoder. Per 64 line bits: NRZI decode in one step (a bit is 1 when the
// level equals the one before it). Then 8 decoded bits at a time (at any bit offset) go
// through one table lookup that hunts for flags or destuffs, and that reports where in
// the window a flag or abort happened, so events cost one lookup too.
#include "sercon/wire/decoder.hpp"

#include <array>
#include <bit>
#include <cstring>
#include <stdexcept>
#include <string>
#include <utility>

#include "receive_rules.hpp"
#include "sercon/wire/fcs.hpp"

namespace sercon::wire {
namespace {

using detail::Action;
using detail::kSaturated;
using detail::RxState;

constexpr std::size_t kMinFrameBytes = 4;  // address + 1 data byte + 2 FCS bytes

// One state machine for hunting and destuffing. State index: 0..7 hunting with that run
// of 1s; 8 + (run | zero_emitted << 3) inside a frame (run 0..6).
constexpr unsigned kFrameStates = 8;
constexpr unsigned kStates = 24;

constexpr unsigned state_index(bool in_frame, RxState s) {
  return in_frame ? kFrameStates + (s.run | (s.zero_emitted ? 8u : 0u)) : s.run;
}

// Table entry for (state, 8 decoded bits MSB first):
//   bits 0..7   the bits delivered to the frame, first at bit 0
//   bits 8..12  state index afterwards (after the event, if any): masked, it is already
//               the next entry's row offset (state * 256), which keeps the loop's chain
//               from one lookup to the next short
//   bits 13..16 how many bits were delivered
//   bits 17..18 event: 0 none, 1 flag, 2 abort; bits 19..21 the window bit it happened at
//   bit 22      zero_emitted at a flag (was the 0 before its six 1s frame data?)
constexpr std::uint32_t kFlagEvent = 1;
constexpr std::uint32_t kAbortEvent = 2;

constexpr std::uint32_t make_entry(unsigned state, unsigned window) {
  bool in_frame = state >= kFrameStates;
  RxState s = in_frame ? RxState{(state - kFrameStates) & 7u, (state - kFrameStates) >= 8}
                       : RxState{state, false};
  std::uint32_t out = 0;
  std::uint32_t count = 0;
  std::uint32_t event = 0;
  std::uint32_t at = 0;
  std::uint32_t flag_zero = 0;
  for (unsigned i = 0; i < 8 && event == 0; ++i) {
    const unsigned bit = (window >> (7 - i)) & 1u;
    const Action a = in_frame ? detail::frame_step(s, bit) : detail::hunt_step(s, bit);
    if (a == Action::Emit0 || a == Action::Emit1) out |= (a == Action::Emit1 ? 1u : 0u) << count++;
    if (a == Action::Flag) {
      event = kFlagEvent;
      flag_zero = s.zero_emitted ? 1 : 0;
      in_frame = true;  // every flag opens a frame
      s = {0, false};
    }
    if (a == Action::Abort) {
      event = kAbortEvent;
      in_frame = false;
    }
    at = i;
  }
  return out | state_index(in_frame, s) << 8 | count << 13 | event << 17 | at << 19 |
         flag_zero << 22;
}

constexpr std::array<std::uint32_t, kStates * 256> make_table() {
  std::array<std::uint32_t, kStates * 256> t{};
  for (unsigned state = 0; state < kStates; ++state)
    if (state < kFrameStates || ((state - kFrameStates) & 7u) <= 6)
      for (unsigned w = 0; w < 256; ++w) t[state * 256 + w] = make_entry(state, w);
  return t;
}

constexpr std::array<std::uint32_t, kStates* 256> kTable = make_table();

std::uint64_t load_be(const std::uint8_t* p) {
  std::uint64_t v;
  std::memcpy(&v, p, 8);
  return __builtin_bswap64(v);
}

std::uint64_t top_mask(unsigned n) { return n == 0 ? 0 : ~std::uint64_t{0} << (64 - n); }

}  // namespace

std::string_view to_string(FrameError error) {
  switch (error) {
    case FrameError::None:
      return "none";
    case FrameError::BadFcs:
      return "bad FCS";
    case FrameError::Abort:
      return "abort (seven 1s in a frame)";
    case FrameError::TooShort:
      return "too short";
    case FrameError::Misaligned:
      return "misaligned (not whole bytes)";
    case FrameError::Truncated:
      return "truncated (input ended in a frame)";
  }
  return "unknown";
}

LineDecoder::LineDecoder(Sink sink) : sink_(std::move(sink)) {
  if (!sink_) throw std::invalid_argument("LineDecoder: empty sink");
}

void LineDecoder::feed(const LineBits& bits) {
  const std::size_t n = bits.size();
  for (std::size_t i = 0; i < n; i += 64)
    feed_word(bits.word_at(i), n - i < 64 ? static_cast<unsigned>(n - i) : 64);
}

void LineDecoder::feed(std::span<const std::uint8_t> packed, std::size_t bit_count) {
  if (bit_count / 8 > packed.size() || (bit_count / 8 == packed.size() && bit_count % 8 != 0))
    throw std::invalid_argument("LineDecoder::feed: " + std::to_string(bit_count) +
                                " bits do not fit in " + std::to_string(packed.size()) + " bytes");
  for (std::size_t i = 0; i < bit_count; i += 64) {
    const std::size_t byte = i / 8;
    std::uint64_t w = 0;
    if (byte + 8 <= packed.size()) {
      w = load_be(packed.data() + byte);
    } else {
      for (std::size_t k = byte; k < packed.size(); ++k)
        w |= static_cast<std::uint64_t>(packed[k]) << (56 - 8 * (k - byte));
    }
    feed_word(w, bit_count - i < 64 ? static_cast<unsigned>(bit_count - i) : 64);
  }
}

void LineDecoder::feed_word(std::uint64_t levels, unsigned count) {
  if (!have_level_) {  // decision: the level before bit 0 is bit 0's own level
    last_level_ = (levels >> 63) != 0;
    have_level_ = true;
  }
  // NRZI (sercos-facts §1): decoded 1 = no level change from the previous bit.
  const std::uint64_t before = (levels >> 1) | (static_cast<std::uint64_t>(last_level_) << 63);
  const std::uint64_t decoded = ~(levels ^ before) & top_mask(count);
  last_level_ = ((levels >> (64 - count)) & 1u) != 0;

  // The stream to work on: pending bits, then this word; up to 71 bits in hi:lo.
  const unsigned n = pending_count_;
  const std::uint64_t hi = pending_ | (decoded >> n);
  const std::uint64_t lo = n == 0 ? 0 : decoded << (64 - n);
  const unsigned total = n + count;
  const std::size_t base = pos_ - n;  // line position of hi's first bit
  // 64 bits from stream bit cur (windows start at <= 63; the leftover may start at 64+).
  auto bits_at = [hi, lo](unsigned cur) {
    if (cur == 0) return hi;
    return cur < 64 ? (hi << cur) | (lo >> (64 - cur)) : lo << (cur - 64);
  };

  // The hot loop keeps the state in locals; events write it back for the handlers.
  unsigned row = state_index(in_frame_, {run_, zero_emitted_}) << 8;  // state * 256
  std::uint64_t acc = acc_;
  unsigned acc_bits = acc_bits_;
  std::uint8_t* bytes = bytes_.data();
  std::size_t nbytes = nbytes_;
  unsigned cur = 0;
  while (cur + 8 <= total) {
    const unsigned row_before = row;
    const std::uint32_t e = kTable[row + static_cast<unsigned>(bits_at(cur) >> 56)];
    acc |= static_cast<std::uint64_t>(e & 0xFFu) << acc_bits;
    acc_bits += (e >> 13) & 0xFu;
    row = e & 0x1F00u;
    if (acc_bits >= 32) {  // store_acc() on the locals
      const auto low = static_cast<std::uint32_t>(acc);
      std::memcpy(bytes + nbytes, &low, 4);
      nbytes += 4;
      acc >>= 32;
      acc_bits -= 32;
      if (nbytes + 8 > bytes_.size()) {
        bytes_.resize(bytes_.size() * 2);
        bytes = bytes_.data();
      }
    }
    const std::uint32_t event = (e >> 17) & 3u;
    if (event == 0) {
      cur += 8;
      continue;
    }
    const unsigned at = (e >> 19) & 7u;
    acc_ = acc;
    acc_bits_ = acc_bits;
    nbytes_ = nbytes;
    in_frame_ = row_before >= kFrameStates << 8;  // the mode the event happened in
    if (event == kFlagEvent) {
      on_flag(base + cur + at, ((e >> 22) & 1u) != 0);
    } else {
      on_abort(base + cur + at);
    }
    acc = acc_;
    acc_bits = acc_bits_;
    nbytes = nbytes_;
    bytes = bytes_.data();
    cur += at + 1;
  }
  const unsigned state = row >> 8;
  in_frame_ = state >= kFrameStates;
  run_ = in_frame_ ? (state - kFrameStates) & 7u : state;
  zero_emitted_ = in_frame_ && (state - kFrameStates) >= 8;
  acc_ = acc;
  acc_bits_ = acc_bits;
  nbytes_ = nbytes;
  pending_count_ = total - cur;
  pending_ = bits_at(cur) & top_mask(pending_count_);
  pos_ += count;
}

void LineDecoder::on_flag(std::size_t pos, bool zero_emitted) {
  // Flag 0 111111 0 ends at pos. Its leading 0 and the first five 1s went into the frame
  // as data (unless that 0 was itself a stuffed or flag 0): take them back.
  if (in_frame_)
    close_frame(pos + 1, emitted_bits() - 5 - (zero_emitted ? 1 : 0), FrameError::None);
  open_frame(pos - 7);
  run_ = 0;
  zero_emitted_ = false;
}

void LineDecoder::on_abort(std::size_t pos) {
  // Seven 1s cannot occur in a frame (sercos-facts §1). The five 1s already taken as data
  // belong to the abort run.
  close_frame(pos + 1, emitted_bits() - 5, FrameError::Abort);
  run_ = kSaturated;
}

void LineDecoder::tail_bits(std::uint64_t decoded_msb_first, unsigned count,
                            std::size_t first_pos) {
  for (unsigned i = 0; i < count; ++i) {
    const unsigned bit = static_cast<unsigned>(decoded_msb_first >> (63 - i)) & 1u;
    RxState s{run_, zero_emitted_};
    const Action a = in_frame_ ? detail::frame_step(s, bit) : detail::hunt_step(s, bit);
    run_ = s.run;
    zero_emitted_ = s.zero_emitted;
    if (a == Action::Emit0 || a == Action::Emit1) emit(a == Action::Emit1 ? 1u : 0u, 1);
    if (a == Action::Flag) on_flag(first_pos + i, s.zero_emitted);
    if (a == Action::Abort) on_abort(first_pos + i);
  }
}

void LineDecoder::store_acc() {
  std::uint32_t low = static_cast<std::uint32_t>(acc_);
  std::memcpy(bytes_.data() + nbytes_, &low, 4);  // little endian: first bits first
  static_assert(std::endian::native == std::endian::little);
  nbytes_ += 4;
  acc_ >>= 32;
  acc_bits_ -= 32;
  if (nbytes_ + 8 > bytes_.size()) bytes_.resize(bytes_.size() * 2);
}

void LineDecoder::open_frame(std::size_t start_bit) {
  in_frame_ = true;
  frame_start_ = start_bit;
  nbytes_ = 0;
  acc_ = 0;
  acc_bits_ = 0;
}

void LineDecoder::close_frame(std::size_t end_bit, std::size_t frame_bits, FrameError forced) {
  in_frame_ = false;
  if (frame_bits < 8) return;  // inter-frame fill, back-to-back flags: not a frame
  const std::size_t n = frame_bits / 8;
  std::memcpy(bytes_.data() + nbytes_, &acc_, 8);  // the last partial word (room kept)
  const std::uint8_t* b = bytes_.data();           // b[0, n): bits of the closing flag dropped
  DecodedFrame& f = frame_;
  f.start_bit = frame_start_;
  f.end_bit = end_bit;
  f.address = b[0];
  f.fcs_received = 0;
  f.fcs_computed = 0;
  f.error = forced;
  if (forced == FrameError::None) {
    if (frame_bits % 8 != 0)
      f.error = FrameError::Misaligned;
    else if (n < kMinFrameBytes)
      f.error = FrameError::TooShort;
  }
  if (f.error == FrameError::None) {
    f.data.assign(b + 1, b + n - 2);
    f.fcs_received = static_cast<std::uint16_t>(b[n - 2] | b[n - 1] << 8);
    f.fcs_computed = fcs16(std::span<const std::uint8_t>(b, n - 2));
    if (f.fcs_received != f.fcs_computed) f.error = FrameError::BadFcs;
  } else {
    f.data.assign(b + 1, b + n);
  }
  sink_(f);
}

void LineDecoder::finish() {
  tail_bits(pending_, pending_count_, pos_ - pending_count_);
  if (in_frame_) close_frame(pos_, emitted_bits(), FrameError::Truncated);
  pos_ = 0;
  have_level_ = false;
  pending_ = 0;
  pending_count_ = 0;
  run_ = kSaturated;
  zero_emitted_ = false;
  in_frame_ = false;
  nbytes_ = 0;
  acc_ = 0;
  acc_bits_ = 0;
}

std::vector<DecodedFrame> decode_all(const LineBits& bits) {
  std::vector<DecodedFrame> frames;
  LineDecoder decoder([&frames](const DecodedFrame& f) { frames.push_back(f); });
  decoder.feed(bits);
  decoder.finish();
  return frames;
}

}  // namespace sercon::wire

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
constexpr unsigned kHuntSaturatedRow = kSaturated << 8;

constexpr unsigned state_index(bool in_frame, RxState s) {
  return in_frame ? kFrameStates + (s.run | (s.zero_emitted ? 8u : 0u)) : s.run;
}

// Table entry for (state, decoded bits MSB first):
//   bits 0..7   the bits delivered to the frame, first at bit 0
//   bits 8..12  state index afterwards (after the event, if any): masked, it is already
//               the next entry's row offset (state * 256), which keeps the loop's chain
//               from one lookup to the next short
//   bits 13..14 event: 0 none, 1 flag, 2 abort; bits 15..17 the window bit it happened at
//   bit 18      zero_emitted at a flag (was the 0 before its six 1s frame data?)
//   bit 19      a frame was open before the window (so at a flag: one closes)
//   bits 28..31 how many bits were delivered (one shift to get it)
constexpr std::uint32_t kFlagEvent = 1;
constexpr std::uint32_t kAbortEvent = 2;
constexpr std::uint32_t kEventMask = 3u << 13;

// The entry for the `width` (1..8) bits of `window` (its low bits), first bit highest.
constexpr std::uint32_t make_entry(unsigned state, unsigned window, unsigned width) {
  bool in_frame = state >= kFrameStates;
  RxState s = in_frame ? RxState{(state - kFrameStates) & 7u, (state - kFrameStates) >= 8}
                       : RxState{state, false};
  std::uint32_t out = 0;
  std::uint32_t count = 0;
  std::uint32_t event = 0;
  std::uint32_t at = 0;
  std::uint32_t flag_zero = 0;
  for (unsigned i = 0; i < width && event == 0; ++i) {
    const unsigned bit = (window >> (width - 1 - i)) & 1u;
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
  return out | state_index(in_frame, s) << 8 | event << 13 | at << 15 | flag_zero << 18 |
         (state >= kFrameStates ? 1u : 0u) << 19 | count << 28;
}

constexpr bool valid_state(unsigned state) {
  return state < kFrameStates || ((state - kFrameStates) & 7u) <= 6;
}

// Full windows: row state * 256, column the next 8 decoded bits.
constexpr std::array<std::uint32_t, kStates * 256> make_table() {
  std::array<std::uint32_t, kStates * 256> t{};
  for (unsigned state = 0; state < kStates; ++state)
    if (valid_state(state))
      for (unsigned w = 0; w < 256; ++w) t[state * 256 + w] = make_entry(state, w, 8);
  return t;
}

// The last k < 8 bits of a feed: column (1 << k) | the k bits, so one row holds every
// width (k = 1..7 use columns 2..255).
constexpr std::array<std::uint32_t, kStates * 256> make_tail_table() {
  std::array<std::uint32_t, kStates * 256> t{};
  for (unsigned state = 0; state < kStates; ++state)
    if (valid_state(state))
      for (unsigned k = 1; k < 8; ++k)
        for (unsigned w = 0; w < (1u << k); ++w)
          t[state * 256 + ((1u << k) | w)] = make_entry(state, w, k);
  return t;
}

constexpr std::array<std::uint32_t, kStates* 256> kTable = make_table();
constexpr std::array<std::uint32_t, kStates* 256> kTailTable = make_tail_table();

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

LineDecoder::LineDecoder(Sink sink) : sink_(std::move(sink)), row_(kHuntSaturatedRow) {
  if (!sink_) throw std::invalid_argument("LineDecoder: empty sink");
}

bool LineDecoder::in_frame() const { return row_ >= kFrameStates << 8; }

void LineDecoder::feed(const LineBits& bits) {
  feed_levels([&bits](std::size_t i) { return bits.word_at(i); }, bits.size());
}

void LineDecoder::feed(std::span<const std::uint8_t> packed, std::size_t bit_count) {
  const std::size_t size = packed.size();
  if (bit_count / 8 > size || (bit_count / 8 == size && bit_count % 8 != 0))
    throw std::invalid_argument("LineDecoder::feed: " + std::to_string(bit_count) +
                                " bits do not fit in " + std::to_string(size) + " bytes");
  if (bit_count == 1 && !have_level_) {
    // A first bit alone (a receiver's lead-in): it only fixes the level reference. It
    // decodes as 1 (decision 1), and a decoder without a level hunts with its run of 1s
    // saturated, which a 1 leaves as it is.
    last_level_ = (packed[0] & 0x80u) != 0;
    have_level_ = true;
    pos_ = 1;
    return;
  }
  const std::uint8_t* p = packed.data();
  feed_levels(
      [p, size](std::size_t i) {
        const std::size_t byte = i / 8;
        if (byte + 8 <= size) return load_be(p + byte);
        // The last bytes: the 8 that end the span, shifted up past the ones already fed.
        if (size >= 8) return load_be(p + size - 8) << (8 * (byte + 8 - size));
        std::uint64_t w = 0;
        for (std::size_t k = byte; k < size; ++k)
          w |= static_cast<std::uint64_t>(p[k]) << (56 - 8 * (k - byte));
        return w;
      },
      bit_count);
}

// NRZI per 64 line bits, then the decoded bits through the tables 8 at a time from `w`
// (decoded bits MSB first, `avail` of them), which the next word tops up.
template <class WordAt>
void LineDecoder::feed_levels(const WordAt& word_at, std::size_t bit_count) {
  if (bit_count == 0) return;
  if (!have_level_) {  // decision: the level before bit 0 is bit 0's own level
    last_level_ = (word_at(0) >> 63) != 0;
    have_level_ = true;
  }
  // The hot loop keeps the state in locals; events write it back for the handlers.
  unsigned row = row_;  // state * 256
  std::uint64_t acc = acc_;
  unsigned acc_bits = acc_bits_;
  std::uint8_t* bytes = frame_bytes();
  std::size_t nbytes = nbytes_;
  std::size_t room_end = frame_capacity() - 8;  // nbytes beyond this: grow
  bool last_level = last_level_;
  std::uint64_t w = 0;
  unsigned avail = 0;
  std::size_t in = pos_;  // one past the last line bit decoded
  unsigned extra = 0;     // decoded bits in `lo` not yet moved into `w`

  // Takes the entry's bits and state.
  const auto deliver = [&](std::uint32_t e) {
    acc |= static_cast<std::uint64_t>(e & 0xFFu) << acc_bits;
    acc_bits += e >> 28;
    row = e & 0x1F00u;
    if (acc_bits >= 32) {
      const auto low = static_cast<std::uint32_t>(acc);
      std::memcpy(bytes + nbytes, &low, 4);  // little endian: first bits first
      nbytes += 4;
      acc >>= 32;
      acc_bits -= 32;
      if (nbytes > room_end) {
        nbytes_ = nbytes;
        grow_frame_bytes();
        bytes = frame_bytes();
        room_end = frame_capacity() - 8;
      }
    }
  };
  // The entry's flag or abort; returns the window bits consumed up to it.
  const auto event = [&](std::uint32_t e) -> unsigned {
    const unsigned at = (e >> 15) & 7u;
    const std::size_t pos = in - extra - avail + at;
    acc_ = acc;
    acc_bits_ = acc_bits;
    nbytes_ = nbytes;
    if (((e >> 13) & 3u) == kFlagEvent) {
      on_flag(pos, ((e >> 18) & 1u) != 0, ((e >> 19) & 1u) != 0);
    } else {
      on_abort(pos);
    }
    acc = acc_;
    acc_bits = acc_bits_;
    nbytes = nbytes_;
    bytes = frame_bytes();
    room_end = frame_capacity() - 8;
    return at + 1;
  };
  const auto full_windows = [&] {
    while (avail >= 8) {
      const std::uint32_t e = kTable[row + static_cast<unsigned>(w >> 56)];
      deliver(e);
      unsigned used = 8;
      if ((e & kEventMask) != 0) [[unlikely]]
        used = event(e);
      w <<= used;
      avail -= used;
    }
  };

  for (std::size_t i = 0; i < bit_count; i += 64) {
    const unsigned count = bit_count - i < 64 ? static_cast<unsigned>(bit_count - i) : 64;
    const std::uint64_t levels = word_at(i);
    // NRZI (sercos-facts §1): decoded 1 = no level change from the previous bit.
    const std::uint64_t before = (levels >> 1) | (static_cast<std::uint64_t>(last_level) << 63);
    const std::uint64_t decoded = ~(levels ^ before) & top_mask(count);
    last_level = ((levels >> (64 - count)) & 1u) != 0;
    in += count;
    std::uint64_t lo = 0;
    if (avail == 0) {
      w = decoded;
      avail = count;
    } else {
      w |= decoded >> avail;
      if (avail + count > 64) {
        lo = decoded << (64 - avail);
        extra = avail + count - 64;
        avail = 64;
      } else {
        avail += count;
      }
    }
    full_windows();
    if (extra != 0) {
      w |= lo >> avail;
      avail += extra;
      extra = 0;
      full_windows();
    }
  }
  while (avail > 0) {  // the last < 8 bits
    const unsigned k = avail;
    const std::uint32_t e = kTailTable[row + ((1u << k) | static_cast<unsigned>(w >> (64 - k)))];
    deliver(e);
    const unsigned used = (e & kEventMask) != 0 ? event(e) : k;
    w <<= used;
    avail -= used;
  }
  row_ = row;
  acc_ = acc;
  acc_bits_ = acc_bits;
  nbytes_ = nbytes;
  last_level_ = last_level;
  pos_ = in;
}

void LineDecoder::grow_frame_bytes() {
  if (heap_.empty()) {
    heap_.assign(inline_.begin(), inline_.end());
  }
  heap_.resize(heap_.size() * 2);
}

void LineDecoder::on_flag(std::size_t pos, bool zero_emitted, bool was_in_frame) {
  // Flag 0 111111 0 ends at pos. Its leading 0 and the first five 1s went into the frame
  // as data (unless that 0 was itself a stuffed or flag 0): take them back.
  if (was_in_frame)
    close_frame(pos + 1, emitted_bits() - 5 - (zero_emitted ? 1 : 0), FrameError::None);
  open_frame(pos - 7);
}

void LineDecoder::on_abort(std::size_t pos) {
  // Seven 1s cannot occur in a frame (sercos-facts §1). The five 1s already taken as data
  // belong to the abort run.
  close_frame(pos + 1, emitted_bits() - 5, FrameError::Abort);
}

void LineDecoder::open_frame(std::size_t start_bit) {
  frame_start_ = start_bit;
  nbytes_ = 0;
  acc_ = 0;
  acc_bits_ = 0;
}

void LineDecoder::close_frame(std::size_t end_bit, std::size_t frame_bits, FrameError forced) {
  if (frame_bits < 8) return;  // inter-frame fill, back-to-back flags: not a frame
  const std::size_t n = frame_bits / 8;
  std::uint8_t* b = frame_bytes();     // b[0, n): bits of the closing flag dropped
  std::memcpy(b + nbytes_, &acc_, 8);  // the last partial word (room kept)
  static_assert(std::endian::native == std::endian::little);
  // The report goes in a frame per thread, whose data keeps its capacity from decoder to
  // decoder (one per burst in the chip model); a decoder run from inside a sink uses its own.
  thread_local DecodedFrame shared;
  thread_local bool shared_in_use = false;
  const bool use_shared = !shared_in_use;
  DecodedFrame& f = use_shared ? shared : frame_;
  struct Release {
    bool* flag;
    ~Release() {
      if (flag != nullptr) *flag = false;
    }
  } release{use_shared ? &shared_in_use : nullptr};
  shared_in_use = true;
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
  if (in_frame()) close_frame(pos_, emitted_bits(), FrameError::Truncated);
  pos_ = 0;
  have_level_ = false;
  row_ = kHuntSaturatedRow;
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

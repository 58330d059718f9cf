// Streaming line decoder. Per 64 line bits: NRZI decode in one step (a bit is 1 when the
// level equals the one before it). Then per decoded byte one table lookup does flag
// hunting or destuffing; only bytes in which a run reaches six 1s (flag or abort) or a
// flag completes take the bit-by-bit path.
#include "sercon/wire/decoder.hpp"

#include <array>
#include <cstring>
#include <stdexcept>
#include <string>
#include <utility>

#include "sercon/wire/fcs.hpp"

namespace sercon::wire {
namespace {

constexpr unsigned kSaturated = 7;      // run of 1s: seven or more (idle, abort, start)
constexpr unsigned kEvent = 0xF;        // frame-table count field: take the slow path
constexpr unsigned kMinFrameBytes = 4;  // address + 1 data byte + 2 FCS bytes

// Hunting (no frame open): entry = run after the byte (bits 0..2), bit 7 set when a flag
// (0 after exactly six 1s) completes inside the byte.
constexpr std::array<std::uint8_t, 8 * 256> make_hunt_table() {
  std::array<std::uint8_t, 8 * 256> table{};
  for (unsigned run0 = 0; run0 < 8; ++run0) {
    for (unsigned byte = 0; byte < 256; ++byte) {
      unsigned run = run0;
      unsigned event = 0;
      for (int i = 7; i >= 0; --i) {  // decoded bits are MSB first (time order)
        if ((byte >> i) & 1u) {
          if (run < kSaturated) ++run;
        } else {
          if (run == 6) event = 1;
          run = 0;
        }
      }
      table[run0 * 256 + byte] = static_cast<std::uint8_t>(run | (event << 7));
    }
  }
  return table;
}

// In a frame, for state = run (0..5) | zero_emitted << 3: the surviving bits in time
// order from bit 0 (bits 0..7), their count (bits 8..11, kEvent if a run reaches six 1s)
// and the state after the byte (bits 12..15).
constexpr std::array<std::uint16_t, 16 * 256> make_frame_table() {
  std::array<std::uint16_t, 16 * 256> table{};
  for (unsigned state = 0; state < 16; ++state) {
    for (unsigned byte = 0; byte < 256; ++byte) {
      unsigned run = state & 7u;
      unsigned zero_emitted = state >> 3;
      unsigned out = 0;
      unsigned count = 0;
      bool event = run > 5;
      for (int i = 7; i >= 0 && !event; --i) {
        if ((byte >> i) & 1u) {
          if (++run == 6) {
            event = true;
          } else {
            out |= 1u << count++;
          }
        } else {
          if (run == 5) {
            zero_emitted = 0;  // stuffed 0 (sercos-facts §1): dropped
          } else {
            ++count;  // a data 0
            zero_emitted = 1;
          }
          run = 0;
        }
      }
      table[state * 256 + byte] =
          event
              ? static_cast<std::uint16_t>(kEvent << 8)
              : static_cast<std::uint16_t>(out | (count << 8) | ((run | zero_emitted << 3) << 12));
    }
  }
  return table;
}

constexpr std::array<std::uint8_t, 8 * 256> kHunt = make_hunt_table();
constexpr std::array<std::uint16_t, 16 * 256> kFrame = make_frame_table();

std::uint64_t load_be(const std::uint8_t* p) {
  std::uint64_t v;
  std::memcpy(&v, p, 8);
  return __builtin_bswap64(v);
}

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
  const std::uint64_t decoded = ~(levels ^ before);
  last_level_ = ((levels >> (64 - count)) & 1u) != 0;

  unsigned k = 0;
  for (; k + 8 <= count; k += 8) {
    const unsigned byte = static_cast<unsigned>(decoded >> (56 - k)) & 0xFFu;
    if (!in_frame_) {
      const std::uint8_t e = kHunt[run_ * 256 + byte];
      if ((e & 0x80u) == 0) {
        run_ = e & 7u;
        continue;
      }
    } else if (run_ <= 5) {
      const unsigned e = kFrame[(run_ | (zero_emitted_ ? 8u : 0u)) * 256 + byte];
      const unsigned n = (e >> 8) & 0xFu;
      if (n != kEvent) {
        emit(e & 0xFFu, n);
        run_ = (e >> 12) & 7u;
        zero_emitted_ = (e & 0x8000u) != 0;
        continue;
      }
    }
    slow_byte(byte, 8, pos_ + k);
  }
  if (k < count) {
    const unsigned rest = count - k;
    slow_byte(static_cast<unsigned>(decoded >> (64 - k - rest)) & ((1u << rest) - 1u), rest,
              pos_ + k);
  }
  pos_ += count;
}

void LineDecoder::slow_byte(std::uint32_t decoded_msb_first, unsigned count,
                            std::size_t first_pos) {
  for (unsigned i = 0; i < count; ++i) {
    if ((decoded_msb_first >> (count - 1 - i)) & 1u)
      on_one(first_pos + i);
    else
      on_zero(first_pos + i);
  }
}

void LineDecoder::on_one(std::size_t pos) {
  if (run_ == kSaturated) return;
  ++run_;
  if (!in_frame_) return;
  if (run_ <= 5) {
    emit(1, 1);
  } else if (run_ == kSaturated) {
    // Seven 1s cannot occur in a frame (sercos-facts §1): abort. The five 1s already
    // taken as data belong to the abort run.
    close_frame(pos + 1, emitted_bits() - 5, FrameError::Abort);
  }
}

void LineDecoder::on_zero(std::size_t pos) {
  if (run_ == 5) {
    zero_emitted_ = false;  // stuffed 0 (sercos-facts §1): dropped
  } else if (run_ == 6) {
    // Flag 0 111111 0 ends here. Its leading 0 and the first five 1s went into the
    // frame as data (unless that 0 was itself a stuffed or flag 0): take them back.
    if (in_frame_)
      close_frame(pos + 1, emitted_bits() - 5 - (zero_emitted_ ? 1 : 0), FrameError::None);
    open_frame(pos - 7);
  } else if (run_ == kSaturated || !in_frame_) {
    zero_emitted_ = false;
  } else {
    emit(0, 1);
    zero_emitted_ = true;
  }
  run_ = 0;
}

void LineDecoder::emit(std::uint32_t lsb_first_bits, unsigned count) {
  acc_ |= static_cast<std::uint64_t>(lsb_first_bits) << acc_bits_;
  acc_bits_ += count;
  if (acc_bits_ >= 8) {
    bytes_.push_back(static_cast<std::uint8_t>(acc_ & 0xFFu));
    acc_ >>= 8;
    acc_bits_ -= 8;
  }
}

void LineDecoder::open_frame(std::size_t start_bit) {
  in_frame_ = true;
  frame_start_ = start_bit;
  bytes_.clear();
  acc_ = 0;
  acc_bits_ = 0;
  zero_emitted_ = false;
}

void LineDecoder::close_frame(std::size_t end_bit, std::size_t frame_bits, FrameError forced) {
  in_frame_ = false;
  if (frame_bits < 8) return;  // inter-frame fill, back-to-back flags: not a frame
  const std::size_t n = frame_bits / 8;
  bytes_.resize(n);  // drops bits that turned out to be the closing flag's
  DecodedFrame& f = frame_;
  f.start_bit = frame_start_;
  f.end_bit = end_bit;
  f.address = bytes_[0];
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
    f.data.assign(bytes_.begin() + 1, bytes_.end() - 2);
    f.fcs_received = static_cast<std::uint16_t>(bytes_[n - 2] | bytes_[n - 1] << 8);
    f.fcs_computed = fcs16(std::span<const std::uint8_t>(bytes_.data(), n - 2));
    if (f.fcs_received != f.fcs_computed) f.error = FrameError::BadFcs;
  } else {
    f.data.assign(bytes_.begin() + 1, bytes_.end());
  }
  sink_(f);
}

void LineDecoder::finish() {
  if (in_frame_) close_frame(pos_, emitted_bits(), FrameError::Truncated);
  pos_ = 0;
  have_level_ = false;
  run_ = kSaturated;
  zero_emitted_ = false;
  in_frame_ = false;
  bytes_.clear();
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

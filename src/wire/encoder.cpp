// Line encoder. Stuffing is one table lookup per byte (state = run of 1s); NRZI is done on
// 64 decoded bits at once with a prefix XOR, since each line level is the XOR of all
// level changes (0 bits) before it.
#include "sercon/wire/encoder.hpp"

#include <array>
#include <bit>
#include <cstring>
#include <stdexcept>
#include <string>
#include <utility>

#include "sercon/wire/encoder_words.hpp"
#include "sercon/wire/fcs.hpp"

namespace sercon::wire {

using namespace encoder_detail;

LineEncoder::LineEncoder(bool initial_level_high) : level_(initial_level_high) {}

LineEncoder::LineEncoder(bool initial_level_high, LineBits buffer)
    : bits_(std::move(buffer)), level_(initial_level_high) {
  bits_.clear();
}

void LineEncoder::put_decoded(std::uint64_t msb_first, unsigned count) {
  Decoded d{pending_, pending_count_, ones_run_};
  put(d, msb_first, count, [this](std::uint64_t w) { put_levels(w, 64); });
  pending_ = d.bits;
  pending_count_ = d.count;
}

void LineEncoder::flush() {
  if (pending_count_ == 0) return;
  put_levels(pending_, pending_count_);
  pending_ = 0;
  pending_count_ = 0;
}

void LineEncoder::put_levels(std::uint64_t decoded, unsigned count) {
  const std::uint64_t x = changes_so_far(~decoded & top_mask(count));  // NRZI
  const std::uint64_t levels = (level_ ? ~x : x) & top_mask(count);
  bits_.append(levels, count);
  level_ = ((levels >> (64 - count)) & 1u) != 0;
}

void LineEncoder::idle(std::size_t bit_count) {
  while (bit_count > 0) {
    const unsigned n = bit_count < 64 ? static_cast<unsigned>(bit_count) : 64;
    const std::uint64_t pattern = std::rotl(kIdlePattern, static_cast<int>(idle_phase_));
    put_decoded(pattern >> (64 - n), n);
    idle_phase_ = (idle_phase_ + n) % 8;
    bit_count -= n;
  }
  ones_run_ = 0;
  flush();
}

void LineEncoder::flag() {
  put_decoded(0x7E, 8);  // 0 111111 0: the same read either way round
  ones_run_ = 0;
  idle_phase_ = 0;
  flush();
}

void LineEncoder::stuff(std::span<const std::uint8_t> bytes) {
  Decoded d{pending_, pending_count_, ones_run_};
  stuff_into(d, bytes, [this](std::uint64_t w) { put_levels(w, 64); });
  pending_ = d.bits;
  pending_count_ = d.count;
  ones_run_ = d.run;
}

void LineEncoder::stuffed_bytes(std::span<const std::uint8_t> bytes) {
  stuff(bytes);
  flush();
}

TelegramCoding encode_telegram(LineBits& out, bool initial_level_high, std::uint8_t address,
                               std::span<const std::uint8_t> data) {
  return encode_telegram_inline(out, initial_level_high, address, data);
}

EncodedFrame LineEncoder::telegram(std::uint8_t address, std::span<const std::uint8_t> data) {
  if (size() == 0 && pending_count_ == 0) {  // a chip's telegram: the word loop
    const TelegramCoding c = encode_telegram(bits_, level_, address, data);
    level_ = c.level_after;
    fcs_ = c.fcs;
    ones_run_ = 0;
    idle_phase_ = 0;
    return c.frame;
  }
  const std::size_t start = size();
  const auto full = [this](std::uint64_t w) { put_levels(w, 64); };
  Decoded d{pending_, pending_count_, 0};
  fcs_ = code_telegram(d, address, data, full);
  if (d.count != 0) put_levels(d.bits, d.count);
  pending_ = 0;
  pending_count_ = 0;
  ones_run_ = 0;
  idle_phase_ = 0;
  return {start, size()};
}

EncodedFrame LineEncoder::raw_frame(std::span<const std::uint8_t> body) {
  const std::size_t start = size();
  put_decoded(0x7E, 8);
  ones_run_ = 0;
  stuff(body);
  put_decoded(0x7E, 8);
  ones_run_ = 0;
  idle_phase_ = 0;
  flush();
  return {start, size()};
}

void LineEncoder::raw_decoded_bits(std::string_view bits) {
  for (char c : bits) {
    if (c != '0' && c != '1')
      throw std::invalid_argument(std::string("LineEncoder::raw_decoded_bits: '") + c +
                                  "' is not a bit");
    put_decoded(c == '1' ? 1u : 0u, 1);
  }
  ones_run_ = 0;
  flush();
}

void LineEncoder::raw_decoded_bits(std::uint64_t bits, unsigned count) {
  if (count > 64) throw std::invalid_argument("LineEncoder::raw_decoded_bits: count > 64");
  for (unsigned i = 0; i < count; ++i) put_decoded((bits >> i) & 1u, 1);
  ones_run_ = 0;
  flush();
}

LineBits LineEncoder::take() {
  LineBits out = std::move(bits_);
  bits_ = LineBits();
  return out;
}

LineBits encode_stream(std::span<const Telegram> telegrams, std::size_t idle_bits_between,
                       bool initial_level_high) {
  LineEncoder enc(initial_level_high);
  enc.idle(idle_bits_between < 8 ? 8 : idle_bits_between);
  for (const Telegram& t : telegrams) {
    enc.telegram(t);
    enc.idle(idle_bits_between);
  }
  return enc.take();
}

}  // namespace sercon::wire

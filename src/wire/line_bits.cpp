// Packed line levels. The buffer keeps 8 spare zero bytes past the last bit so appends
// and word reads are one unaligned 64-bit big-endian access (MSB first = time order).
#include "sercon/wire/line_bits.hpp"

#include <algorithm>
#include <cstring>
#include <stdexcept>
#include <string>

namespace sercon::wire {
namespace {

std::uint64_t load_be(const std::uint8_t* p) {
  std::uint64_t v;
  std::memcpy(&v, p, 8);
  return __builtin_bswap64(v);
}

void store_be(std::uint8_t* p, std::uint64_t v) {
  v = __builtin_bswap64(v);
  std::memcpy(p, &v, 8);
}

}  // namespace

LineBits LineBits::from_packed(std::vector<std::uint8_t> bytes, std::size_t bit_count) {
  if (bit_count / 8 > bytes.size() || (bit_count / 8 == bytes.size() && bit_count % 8 != 0))
    throw std::invalid_argument("LineBits::from_packed: " + std::to_string(bit_count) +
                                " bits do not fit in " + std::to_string(bytes.size()) + " bytes");
  LineBits out;
  out.size_ = bit_count;
  bytes.resize((bit_count + 7) / 8);  // drop bytes past the last bit, then add the zero tail
  bytes.resize(bytes.size() + 8, 0);
  if (bit_count % 8 != 0)  // clear the unused low bits of the last byte
    bytes[bit_count / 8] &= static_cast<std::uint8_t>(0xFFu << (8 - bit_count % 8));
  out.buf_ = std::move(bytes);
  return out;
}

bool LineBits::at(std::size_t i) const {
  if (i >= size_)
    throw std::out_of_range("LineBits::at: bit " + std::to_string(i) + " of " +
                            std::to_string(size_));
  return level(i);
}

void LineBits::ensure_capacity(std::size_t bit_count) {
  const std::size_t need = (bit_count + 7) / 8 + 8;
  if (buf_.size() < need) buf_.resize(std::max(need, buf_.size() * 2), 0);
}

void LineBits::grow(std::size_t bit_count) { buf_.resize((bit_count + 7) / 8 + 8, 0); }

void LineBits::append(std::uint64_t msb_first, unsigned count) {
  if (count == 0) return;
  if (count > 64) throw std::invalid_argument("LineBits::append: more than 64 bits");
  if (count < 64) msb_first &= ~(~std::uint64_t{0} >> count);  // keep the buffer's 0 tail
  ensure_capacity(size_ + count);
  std::uint8_t* p = buf_.data() + size_ / 8;
  const unsigned off = static_cast<unsigned>(size_ % 8);
  store_be(p, load_be(p) | (msb_first >> off));
  if (off != 0) p[8] = static_cast<std::uint8_t>(p[8] | (msb_first << (64 - off)) >> 56);
  size_ += count;
}

void LineBits::append_run(bool high, std::size_t count) {
  if (!high) {  // the tail is already zero: just grow
    ensure_capacity(size_ + count);
    size_ += count;
    return;
  }
  ensure_capacity(size_ + count);
  for (; count >= 64; count -= 64) append(~std::uint64_t{0}, 64);
  append(~std::uint64_t{0}, static_cast<unsigned>(count));
}

void LineBits::append(const LineBits& other) {
  ensure_capacity(size_ + other.size_);
  std::size_t i = 0;
  for (; i + 64 <= other.size_; i += 64) append(other.word_at(i), 64);
  append(other.word_at(i), static_cast<unsigned>(other.size_ - i));
}

void LineBits::clear() {
  std::fill(buf_.begin(), buf_.begin() + static_cast<std::ptrdiff_t>((size_ + 7) / 8), 0);
  size_ = 0;
}

std::uint64_t LineBits::word_at(std::size_t first) const {
  if (first >= size_) return 0;
  const std::uint8_t* p = buf_.data() + first / 8;
  const unsigned off = static_cast<unsigned>(first % 8);
  std::uint64_t w = load_be(p) << off;
  if (off != 0) w |= static_cast<std::uint64_t>(p[8]) >> (8 - off);
  return w;  // bits past size_ are zero in the buffer
}

std::vector<std::uint8_t> LineBits::packed_copy() const {
  const auto p = packed();
  return {p.begin(), p.end()};
}

bool operator==(const LineBits& a, const LineBits& b) {
  if (a.size_ != b.size_) return false;
  const auto pa = a.packed();
  const auto pb = b.packed();
  return std::equal(pa.begin(), pa.end(), pb.begin());
}

}  // namespace sercon::wire

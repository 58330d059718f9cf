// A packed sequence of line levels (1 = high), in time order. The packing is the on-disk
// `bits` capture format: MSB first within each byte, bit i is (bytes[i/8] >> (7 - i%8)) & 1.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <span>
#include <vector>

namespace sercon::wire {

class LineBits {
 public:
  LineBits() = default;

  // Takes ownership of packed bytes holding bit_count levels; bits past bit_count are
  // ignored (and cleared). Throws std::invalid_argument if bit_count > 8 * bytes.size().
  static LineBits from_packed(std::vector<std::uint8_t> bytes, std::size_t bit_count);

  std::size_t size() const { return size_; }
  bool empty() const { return size_ == 0; }
  // Level of bit i (precondition i < size(); at() checks and throws std::out_of_range).
  bool level(std::size_t i) const { return ((unsigned{buf_[i >> 3]} >> (7 - (i & 7))) & 1u) != 0; }
  bool operator[](std::size_t i) const { return level(i); }
  bool at(std::size_t i) const;

  void push_back(bool high) { append(high ? ~std::uint64_t{0} : 0, 1); }
  // Appends the `count` (0..64) most significant bits of `msb_first`, the MSB first.
  void append(std::uint64_t msb_first, unsigned count);
  // Appends `count` copies of one level.
  void append_run(bool high, std::size_t count);
  void append(const LineBits& other);
  // The encoder's word loop, without checks: after drop_for_overwrite() and a reserve() of
  // the bits to come plus a word, whole 8-byte words are stored from reserved_bytes() on
  // (store_word), then written() sets the bit count (the last word's bits past it 0). The
  // writer keeps its place in a register, not size() in memory after every store.
  std::uint8_t* reserved_bytes() { return buf_.data(); }
  // The 64 bits of `msb_first` at `to`, MSB first.
  static void store_word(std::uint8_t* to, std::uint64_t msb_first) {
    const std::uint64_t be = __builtin_bswap64(msb_first);
    std::memcpy(to, &be, 8);
  }
  void written(std::size_t bit_count) { size_ = bit_count; }
  // Room for bit_count bits (and the word past them); inline: a telegram's buffer, used
  // before, has it already.
  void reserve(std::size_t bit_count) {
    if (buf_.size() < (bit_count + 7) / 8 + 8) grow(bit_count);
  }
  void clear();
  // For a writer that writes at least `min_bytes` whole bytes again from bit 0 with
  // store_word (the encoder): drops the bits, clearing only their bytes past those
  // (cheaper than clear() first). The writer's last word leaves 0s past its bits.
  void drop_for_overwrite(std::size_t min_bytes) {
    const std::size_t bytes = (size_ + 7) / 8;
    // 8 at a time: the buffer has 8 bytes past the old bits (its end may be cleared twice).
    for (std::size_t i = min_bytes; i < bytes; i += 8) std::memset(buf_.data() + i, 0, 8);
    size_ = 0;
  }

  // 64 bits starting at bit `first` (any position), MSB = bit `first`; bits past size()
  // read as 0. This is how the codec reads the line a word at a time.
  std::uint64_t word_at(std::size_t first) const;

  // The packed bytes, ceil(size()/8) of them; unused low bits of the last byte are 0.
  std::span<const std::uint8_t> packed() const { return {buf_.data(), (size_ + 7) / 8}; }
  std::vector<std::uint8_t> packed_copy() const;

  friend bool operator==(const LineBits& a, const LineBits& b);

 private:
  void ensure_capacity(std::size_t bit_count);
  void grow(std::size_t bit_count);  // reserve()'s allocation

  // Empty until the first bit (an empty line allocates nothing: the chip makes and drops
  // many), then at least ceil(size_/8) + 8 bytes so a word can be read or written at any
  // bit position without bounds checks; bytes past the last bit are 0.
  std::vector<std::uint8_t> buf_;
  std::size_t size_ = 0;
};

}  // namespace sercon::wire

// The telegram processor's view of the DPRAM: word accesses through the chip's internal
// RAM port (so BUSYN sees them), with the bounds check that turns bad pointers into a
// defined list fault instead of an out-of-range access (docs/telegram-processing.md,
// "Bad lists").
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <span>
#include <stdexcept>

#include "sercon/chip/chip.hpp"

namespace sercon::chip {

// A list structure reaches beyond the RAM, loops, or has no valid kind. Thrown by the
// walk, caught where a list item is handled: that list stops for the rest of the cycle.
class ListFault : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Throws ListFault(`what`). Out of line and cold: a throw written in place makes the hot
// functions around it build the exception inline (a list walk checks at every word).
[[noreturn, gnu::cold, gnu::noinline]] inline void throw_list_fault(const char* what) {
  throw ListFault(what);
}

class TelegramRam {
 public:
  explicit TelegramRam(Chip& chip) : port_(chip.tp_ram_port()), size_(port_.size()) {}

  std::uint16_t size() const { return size_; }
  bool contains(std::uint32_t word) const { return word < size_; }

  // One bounds check here, then the chip's port unchecked (Chip::TpRamPort).
  std::uint16_t read(std::uint32_t word) {
    check(word);
    return port_.read(static_cast<std::uint16_t>(word));
  }
  void write(std::uint32_t word, std::uint16_t value) {
    check(word);
    port_.write(static_cast<std::uint16_t>(word), value);
  }
  // read(word) and then write(word, change(value read)), with one bounds check; returns the
  // value read.
  template <class Change>
  std::uint16_t update(std::uint32_t word, Change change) {
    check(word);
    return port_.update(static_cast<std::uint16_t>(word), change);
  }
  // Words first .. first + out.size() - 1, as one read() each: the words inside the RAM
  // are read (and marked for BUSYN), then a ListFault if the run reaches beyond it.
  void read_run(std::uint32_t first, std::span<std::uint16_t> out) {
    in_ram(first, out.size(),
           [&](std::size_t n) { port_.read_run(static_cast<std::uint16_t>(first), out.first(n)); });
  }
  // The same for writes.
  void write_run(std::uint32_t first, std::span<const std::uint16_t> words) {
    in_ram(first, words.size(), [&](std::size_t n) {
      port_.write_run(static_cast<std::uint16_t>(first), words.first(n));
    });
  }
  // The same for `count` words given as little-endian byte pairs.
  void write_run_le(std::uint32_t first, const std::uint8_t* bytes, std::size_t count) {
    in_ram(first, count,
           [&](std::size_t n) { port_.write_run_le(static_cast<std::uint16_t>(first), bytes, n); });
  }
  // The RAM's words, read without a mark: for a caller that looks at a structure first and
  // then marks what it read as one run (touch_run). Each word read must be < size().
  const std::uint16_t* words() const { return port_.words(); }
  // The same for writing (each word written must be < size(), and marked with touch_run or
  // update_and_touch_run).
  std::uint16_t* words_to_write() { return port_.words_to_write(); }
  // update(word, change) and touch_run(first, count) at one instant, for words the caller
  // has checked to be < size().
  template <class Change>
  std::uint16_t update_and_touch_run(std::uint16_t word, Change change, std::uint16_t first,
                                     std::size_t count) {
    return port_.update_and_touch_run(word, change, first, count);
  }
  // read(word) (its value not wanted) and touch_run(first, count) at one instant, for words
  // the caller has checked to be < size().
  void read_and_touch_run(std::uint16_t word, std::uint16_t first, std::size_t count) {
    port_.read_and_touch_run(word, first, count);
  }
  // Words first .. first + count - 1 read now: marked and counted as read_run() does (and a
  // ListFault likewise if the run reaches beyond the RAM).
  void touch_run(std::uint32_t first, std::size_t count) {
    in_ram(first, count,
           [&](std::size_t n) { port_.touch_run(static_cast<std::uint16_t>(first), n); });
  }
  // touch_run() for words the caller has checked to be < size() (no second bounds check).
  void touch_checked_run(std::uint16_t first, std::size_t count) { port_.touch_run(first, count); }
  // Error counters (NERR, NMSTERR) stop at 0xFFFF rather than wrap to small numbers.
  void count_error(std::uint32_t word) {
    const std::uint16_t n = read(word);
    if (n != 0xFFFF)
      port_.write(static_cast<std::uint16_t>(word), static_cast<std::uint16_t>(n + 1));
  }

 private:
  // A run of `count` words from `first`: `part(n)` on its first n words, those inside the
  // RAM (all of them, the usual case, in one call), then a ListFault if some are beyond.
  // Always inline: GCC made read_run's a call of its own, about 20 instructions a run more.
  template <class Part>
  [[gnu::always_inline]] void in_ram(std::uint32_t first, std::size_t count, Part part) {
    if (first + count <= size_) return part(count);
    const std::size_t inside = first >= size_ ? 0 : std::min<std::size_t>(count, size_ - first);
    if (inside != 0) part(inside);
    if (inside < count) throw_list_fault("list structure beyond the RAM");
  }
  void check(std::uint32_t word) const {
    if (word >= size_) throw_list_fault("list structure beyond the RAM");
  }

  Chip::TpRamPort port_;
  std::uint16_t size_;
};

}  // namespace sercon::chip

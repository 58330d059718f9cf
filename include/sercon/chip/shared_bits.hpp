// A telegram's line bits as they travel: one object shared by every hop that passes them on
// unchanged (a hop that changes them, a bit error, makes its own), carrying what the
// receivers have decoded from them, so a telegram that crosses a ring of repeaters is
// decoded once (line_decode_memo.hpp).
//
// Counted without atomics: a telegram crosses its ring at every hop, and an atomic count
// there cost a measurable share of a ring's time (docs/performance.md, "Ring"). So a bits
// object belongs to one simulation and the thread that runs it, like every other object
// of that simulation.
#pragma once

#include <cstddef>
#include <memory>
#include <utility>
#include <vector>

#include "sercon/wire/decoder.hpp"
#include "sercon/wire/line_bits.hpp"

namespace sercon::chip {

// The frames a receiver finds in one burst. Bit positions count from the burst's first bit.
struct BurstDecode {
  std::vector<wire::DecodedFrame> frames;
  std::vector<std::size_t> address_end;  // per frame: one past the address byte's last bit
};

// Decodes made from one bits object, kept with it (filled by line_decode_memo.cpp).
struct BurstDecodes {
  std::unique_ptr<const BurstDecode> whole;
  // The burst cut after a line bit (a telegram cut by the next change), per cut position.
  std::vector<std::pair<std::size_t, std::unique_ptr<const BurstDecode>>> prefixes;
};

class SharedBits {
 public:
  SharedBits() = default;
  SharedBits(std::nullptr_t) {}  // NOLINT: a null handle reads like a null pointer

  SharedBits(const SharedBits& other) noexcept : node_(other.node_) {
    if (node_) ++node_->count;
  }
  SharedBits(SharedBits&& other) noexcept : node_(std::exchange(other.node_, nullptr)) {}
  SharedBits& operator=(const SharedBits& other) noexcept {
    SharedBits copy(other);
    std::swap(node_, copy.node_);
    return *this;
  }
  SharedBits& operator=(SharedBits&& other) noexcept {
    SharedBits moved(std::move(other));
    std::swap(node_, moved.node_);
    return *this;
  }
  ~SharedBits() {
    if (node_ && --node_->count == 0) delete node_;
  }

  const wire::LineBits* get() const { return node_ ? &node_->bits : nullptr; }
  const wire::LineBits& operator*() const { return node_->bits; }
  const wire::LineBits* operator->() const { return &node_->bits; }
  explicit operator bool() const { return node_ != nullptr; }
  friend bool operator==(const SharedBits& a, const SharedBits& b) { return a.node_ == b.node_; }

  // The decodes of these bits (precondition: not null). A cache: filling it does not change
  // the bits, so it may be filled through a const handle.
  BurstDecodes& decodes() const { return node_->decodes; }

 private:
  struct Node {
    explicit Node(wire::LineBits b) : bits(std::move(b)) {}
    wire::LineBits bits;
    std::size_t count = 1;
    BurstDecodes decodes;
  };
  explicit SharedBits(Node* node) : node_(node) {}
  friend SharedBits share_bits(wire::LineBits bits);

  Node* node_ = nullptr;
};

// The one way to make bits to share: a new object, counted from one.
inline SharedBits share_bits(wire::LineBits bits) {
  return SharedBits(new SharedBits::Node(std::move(bits)));
}

}  // namespace sercon::chip

// A telegram's line bits as they travel: one object shared by every hop that passes them on
// unchanged (a hop that changes them, a bit error, makes its own), carrying what the
// receivers have decoded from them, so a telegram that crosses a ring of repeaters is
// decoded once (line_decode_memo.hpp).
//
// Counted without atomics: a telegram crosses its ring at every hop, and an atomic count
// there cost a measurable share of a ring's time (docs/performance.md, "Ring"). So a bits
// object belongs to one simulation and the thread that runs it, like every other object
// of that simulation.
//
// Recycled: a released object goes to a free list of the thread that releases it, with its
// bit buffer and its whole decode's storage, and the next one made on that thread takes it,
// so a chip sending a telegram per cycle allocates nothing once its ring is warm
// (docs/serial-and-ring.md, "Bits objects are recycled").
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <utility>
#include <vector>

#include "sercon/wire/decoder.hpp"
#include "sercon/wire/line_bits.hpp"

namespace sercon::chip {

// Under AddressSanitizer nothing is recycled: a pointer kept into a released decode must
// show as a use after free, not read another telegram's frames.
#if defined(__SANITIZE_ADDRESS__)
inline constexpr bool kRecycleBits = false;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
inline constexpr bool kRecycleBits = false;
#else
inline constexpr bool kRecycleBits = true;
#endif
#else
inline constexpr bool kRecycleBits = true;
#endif

// Address 255: MSTs and telegrams to all drives (sercos-facts §2), the one address the
// receiver, the decode and the telegram list single out.
inline constexpr std::uint8_t kAddress255 = 0xFF;

// The frames a receiver finds in one burst. Bit positions count from the burst's first bit.
struct BurstDecode {
  std::vector<wire::DecodedFrame> frames;
  std::vector<std::size_t> address_end;  // per frame: one past the address byte's last bit
  // Some frame is addressed 255 (an MST, a telegram to all drives): a lazy hop past a chip
  // that waits for no telegram need look no further when none is.
  bool to_255 = false;
};

// Decodes made from one bits object, kept with it (filled by line_decode_memo.cpp).
struct BurstDecodes {
  std::unique_ptr<const BurstDecode> whole;
  // The burst cut after a line bit (a telegram cut by the next change), per cut position.
  std::vector<std::pair<std::size_t, std::unique_ptr<const BurstDecode>>> prefixes;
  // A decode kept for filling again: fresh_node() moves a pooled object's whole decode
  // here (encode_seeded() fills `whole` in place instead, line_decode_memo.cpp).
  std::unique_ptr<BurstDecode> spare;
};

class SharedBits {
 public:
  SharedBits() = default;
  SharedBits(std::nullptr_t) {}  // NOLINT: a null handle reads like a null pointer

  SharedBits(const SharedBits& other) noexcept : node_(other.node_) {
    if (node_) ++node_->count;
  }
  SharedBits(SharedBits&& other) noexcept : node_(std::exchange(other.node_, nullptr)) {}
  // The same bits again (a lazy hop's fibre sets the burst to what it holds already) count
  // nothing.
  SharedBits& operator=(const SharedBits& other) noexcept {
    Node* const n = other.node_;
    if (n == node_) return *this;
    if (n) ++n->count;
    drop(std::exchange(node_, n));
    return *this;
  }
  // operator=() of a handle known to hold bits (a lazy hop's burst, checked where it came
  // in): counted up first, so the same bits again come out even without the comparison.
  // Always inline: GCC made it a call at some of the settle's writes.
  [[gnu::always_inline]] void assign_held(const SharedBits& other) noexcept {
    Node* const n = other.node_;
    ++n->count;
    drop(std::exchange(node_, n));
  }
  SharedBits& operator=(SharedBits&& other) noexcept {
    Node* const n = std::exchange(other.node_, nullptr);  // first: `other` may be *this
    drop(std::exchange(node_, n));
    return *this;
  }
  ~SharedBits() { drop(node_); }

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
    wire::LineBits bits;
    std::size_t count = 1;
    BurstDecodes decodes;
  };
  // More than a ring has telegrams under way: 254 slaves let some 256 go together at the
  // end of a cycle, and each one not kept is freed and allocated again the next cycle.
  static constexpr std::size_t kMaxPooled = 1024;
  // Plain data, constant-initialised (constinit here too), so that the hot paths find it
  // without a thread-local initialisation check.
  struct Pool {
    Node* free[kMaxPooled];  // [0, size): count 1, bits and decodes as last left
    std::size_t size;
    // How many may be kept: kMaxPooled once pool_cleanup_ is made for this thread (and 0
    // without recycling, and again from thread exit on), so that release() asks one bound.
    std::size_t room;
    bool gone;          // set at thread exit: what is released after that is freed
    bool cleanup_made;  // pool_cleanup_ made for this thread (arm_cleanup())
  };
  struct PoolCleanup;
  static thread_local constinit Pool pool_;
  static thread_local PoolCleanup pool_cleanup_;
  explicit SharedBits(Node* node) : node_(node) {}
  static Node* fresh_node();  // counted from one, bits empty, no decodes (shared_bits.cpp)
  // Counted from one, bits and decodes as the last holder left them (or empty). Inline: at
  // every telegram sent.
  static Node* recycled_node() {
    if (pool_.size != 0) [[likely]]
      return pool_.free[--pool_.size];
    return allocate();
  }
  [[gnu::noinline, gnu::cold]] static void arm_cleanup();  // this thread's pool is freed at exit
  [[gnu::noinline]] static Node* allocate();               // a new object, on a pool's first use
  static void release(Node* node) noexcept;
  [[gnu::noinline, gnu::cold]] static void destroy(Node* node) noexcept;
  static void drop(Node* node) noexcept {
    if (node && --node->count == 0) release(node);
  }
  friend SharedBits share_bits(wire::LineBits bits);
  template <class Write>
  friend SharedBits write_shared_bits(Write&& write);
  template <class Rewrite>
  friend SharedBits rewrite_shared_bits(Rewrite&& rewrite);

  Node* node_ = nullptr;
};

// Bits to share: a new object, counted from one.
inline SharedBits share_bits(wire::LineBits bits) {
  SharedBits shared(SharedBits::fresh_node());
  shared.node_->bits = std::move(bits);
  return shared;
}

// The same, written in place: `write` gets the new object's bits, empty, in a buffer a
// released object may have used (so a steady stream of telegrams allocates nothing).
template <class Write>
SharedBits write_shared_bits(Write&& write) {
  SharedBits shared(SharedBits::fresh_node());
  write(shared.node_->bits);
  return shared;
}

// The same, written over a recycled object as its last holder left it: `rewrite` gets its
// bits and decodes, either empty or as they were, and must set every bit and field again
// (the transmitter's telegrams, line_decode_memo.hpp: encode_seeded). Cheaper than
// clearing them for the writer to fill again.
template <class Rewrite>
SharedBits rewrite_shared_bits(Rewrite&& rewrite) {
  SharedBits shared(SharedBits::recycled_node());
  rewrite(shared.node_->bits, shared.node_->decodes);
  return shared;
}

}  // namespace sercon::chip

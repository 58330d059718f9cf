// The free list of bits objects (shared_bits.hpp, "Recycled"): one per thread, as a bits
// object belongs to the thread that runs its simulation.
#include "sercon/chip/shared_bits.hpp"

#include <memory>

namespace sercon::chip {
namespace {

// A buffer longer than this (not a telegram: a test's long stream) is not kept.
constexpr std::size_t kMaxKeptBits = 64 * 1024;

}  // namespace

// Frees the pool's objects at thread exit. Made (and so registered) by the first object
// the thread allocates or pools (arm_cleanup()): a thread may release objects
// another made (a ring built on one thread and run on another).
struct SharedBits::PoolCleanup {
  bool armed = false;
  ~PoolCleanup() {
    pool_.gone = true;
    pool_.room = 0;
    for (std::size_t i = 0; i < pool_.size; ++i) delete pool_.free[i];
    pool_.size = 0;
  }
};

thread_local constinit SharedBits::Pool SharedBits::pool_{};

thread_local SharedBits::PoolCleanup SharedBits::pool_cleanup_;

// Touching pool_cleanup_ makes it for this thread, and so registers its destructor: once,
// out of line (its thread-local wrapper is a call).
void SharedBits::arm_cleanup() {
  pool_cleanup_.armed = true;
  pool_.cleanup_made = true;
  pool_.room = kRecycleBits ? kMaxPooled : 0;
}

SharedBits::Node* SharedBits::allocate() {
  if (!pool_.cleanup_made) arm_cleanup();
  return new Node();
}

SharedBits::Node* SharedBits::fresh_node() {
  Node* n = recycled_node();
  if (!n->bits.empty()) n->bits.clear();
  BurstDecodes& d = n->decodes;
  // Made non-const (line_decode_memo.cpp), so it may be filled again.
  if (d.whole && !d.spare) d.spare.reset(const_cast<BurstDecode*>(d.whole.release()));
  d.whole.reset();
  d.prefixes.clear();
  return n;
}

// Kept as it is: its next taker writes it over (rewrite_shared_bits) or clears it
// (fresh_node), so a telegram's object is not cleared only to be filled again.
void SharedBits::release(Node* n) noexcept {
  if (pool_.size < pool_.room && n->bits.size() <= kMaxKeptBits) [[likely]] {
    n->count = 1;
    pool_.free[pool_.size++] = n;
    return;
  }
  // The pool not made yet on this thread (its first release): made, then asked again.
  if (kRecycleBits && !pool_.gone && !pool_.cleanup_made) {
    arm_cleanup();
    return release(n);
  }
  destroy(n);
}

// Out of line, so that release() saves no registers for it.
void SharedBits::destroy(Node* n) noexcept { delete n; }

}  // namespace sercon::chip

// The free list of bits objects (shared_bits.hpp, "Recycled"): one per thread, as a bits
// object belongs to the thread that runs its simulation.
#include "sercon/chip/shared_bits.hpp"

#include <vector>

namespace sercon::chip {
namespace {

// More than a ring has telegrams under way: 254 slaves let some 256 go together at the end
// of a cycle, and each one not kept is freed and allocated again the next cycle.
constexpr std::size_t kMaxPooled = 1024;
// A buffer longer than this (not a telegram: a test's long stream) is not kept.
constexpr std::size_t kMaxKeptBits = 64 * 1024;

// Set when this thread's pool is gone (thread exit): what is released after that is freed.
thread_local bool pool_gone = false;

}  // namespace

struct SharedBits::Pool {
  Pool() { free.reserve(kMaxPooled); }
  ~Pool() {
    pool_gone = true;
    for (Node* n : free) delete n;
  }
  Pool(const Pool&) = delete;
  Pool& operator=(const Pool&) = delete;
  std::vector<Node*> free;  // bits empty, count 1, no decodes (a spare one kept)
};

thread_local SharedBits::Pool SharedBits::pool_;

SharedBits::Node* SharedBits::fresh_node() {
  if (!kRecycleBits || pool_gone || pool_.free.empty()) return new Node();
  Node* n = pool_.free.back();
  pool_.free.pop_back();
  return n;
}

void SharedBits::release(Node* n) noexcept {
  if (!kRecycleBits || pool_gone || pool_.free.size() >= kMaxPooled ||
      n->bits.size() > kMaxKeptBits) {
    delete n;
    return;
  }
  n->bits.clear();
  n->count = 1;
  BurstDecodes& d = n->decodes;
  // Made non-const (line_decode_memo.cpp), so it may be filled again.
  if (d.whole && !d.spare) d.spare.reset(const_cast<BurstDecode*>(d.whole.release()));
  d.whole.reset();
  d.prefixes.clear();
  pool_.free.push_back(n);  // within the capacity reserved: no allocation
}

}  // namespace sercon::chip

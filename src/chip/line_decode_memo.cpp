#include "sercon/chip/line_decode_memo.hpp"

#include <algorithm>
#include <unordered_map>
#include <utility>

#include "sercon/chip/line_length.hpp"

namespace sercon::chip {
namespace {

struct Entry {
  std::weak_ptr<const wire::LineBits> owner;  // tells a reused address from the same bits
  std::shared_ptr<const BurstDecode> whole;
  std::vector<std::pair<std::size_t, std::shared_ptr<const BurstDecode>>> prefixes;
};

// The weak_ptr keeps its control block alive, so an equal owner is the very same bits.
bool same_owner(const std::weak_ptr<const wire::LineBits>& w, const SharedBits& bits) {
  return !w.owner_before(bits) && !bits.owner_before(w);
}

struct Memo {
  std::unordered_map<const wire::LineBits*, Entry> entries;
  std::size_t purge_at = 256;
  std::size_t decodes = 0;
  // The last whole decode: around a ring every receiver asks for the same bits in a row.
  std::weak_ptr<const wire::LineBits> last_owner;
  std::shared_ptr<const BurstDecode> last_decode;

  Entry& entry(const SharedBits& bits) {
    auto [it, inserted] = entries.try_emplace(bits.get());
    Entry& e = it->second;
    if (!inserted && !same_owner(e.owner, bits)) e = Entry{};  // old bits died, same address
    if (inserted || e.owner.expired()) e.owner = bits;
    if (inserted && entries.size() >= purge_at) purge(bits.get());
    return entries.at(bits.get());
  }

  // Drops entries whose bits are gone; keeps the memo proportional to live bursts.
  void purge(const wire::LineBits* keep) {
    std::erase_if(entries,
                  [keep](const auto& kv) { return kv.first != keep && kv.second.owner.expired(); });
    purge_at = std::max<std::size_t>(256, 2 * entries.size());
  }
};

thread_local Memo memo;

// Feeds the lead-in level, then `count` bits of `bits`, then `dark_tail` bits without
// edges, and collects the frames with positions counted from the burst's first bit.
std::shared_ptr<const BurstDecode> run_decoder(const wire::LineBits& bits, std::size_t count,
                                               std::size_t dark_tail) {
  auto result = std::make_shared<BurstDecode>();
  ++memo.decodes;
  if (count == 0) return result;
  wire::LineDecoder decoder([&result](const wire::DecodedFrame& frame) {
    wire::DecodedFrame f = frame;
    f.start_bit -= 1;  // the lead-in bit
    f.end_bit -= 1;
    result->address_end.push_back(f.start_bit + address_end_bit(f.address));
    result->frames.push_back(std::move(f));
  });
  wire::LineBits lead_in;
  lead_in.push_back(!bits.level(0));
  decoder.feed(lead_in);
  decoder.feed(bits.packed(), count);
  if (dark_tail > 0) {
    wire::LineBits tail;
    tail.append_run(bits.level(count - 1), dark_tail);
    decoder.feed(tail);
  }
  decoder.finish();
  return result;
}

}  // namespace

std::shared_ptr<const BurstDecode> decode_burst(const SharedBits& bits) {
  if (memo.last_decode && same_owner(memo.last_owner, bits)) return memo.last_decode;
  Entry& e = memo.entry(bits);
  if (!e.whole) e.whole = run_decoder(*bits, bits->size(), 0);
  memo.last_owner = bits;
  memo.last_decode = e.whole;
  return e.whole;
}

std::shared_ptr<const BurstDecode> decode_burst_prefix(const SharedBits& bits,
                                                       std::size_t cut_bit) {
  Entry& e = memo.entry(bits);
  for (const auto& [cut, decode] : e.prefixes) {
    if (cut == cut_bit) return decode;
  }
  auto decode = run_decoder(*bits, std::min(cut_bit, bits->size()), 8);
  e.prefixes.emplace_back(cut_bit, decode);
  return decode;
}

std::size_t burst_decode_count() { return memo.decodes; }

}  // namespace sercon::chip

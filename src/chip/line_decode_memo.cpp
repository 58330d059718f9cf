#include "sercon/chip/line_decode_memo.hpp"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <memory>
#include <span>
#include <utility>

#include "sercon/chip/line_decode_seed.hpp"
#include "sercon/chip/line_length.hpp"

namespace sercon::chip {

thread_local constinit std::size_t seed_detail::decodes = 0;

namespace {

using seed_detail::decodes;

// Feeds the lead-in level, then `count` bits of `bits`, then `dark_tail` bits without
// edges, and collects the frames with positions counted from the burst's first bit.
std::unique_ptr<const BurstDecode> run_decoder(const wire::LineBits& bits, std::size_t count,
                                               std::size_t dark_tail) {
  auto result = std::make_unique<BurstDecode>();
  ++decodes;
  if (count == 0) return result;
  result->frames.reserve(1);  // a burst is one telegram, but for collisions and cuts
  result->address_end.reserve(1);
  wire::LineDecoder decoder([&result](const wire::DecodedFrame& frame) {
    wire::DecodedFrame f = frame;
    f.start_bit -= 1;  // the lead-in bit
    f.end_bit -= 1;
    result->address_end.push_back(f.start_bit + address_end_bit(f.address));
    result->to_255 = result->to_255 || f.address == kAddress255;
    result->frames.push_back(std::move(f));
  });
  const std::uint8_t lead_in = bits.level(0) ? 0x00 : 0x80;  // the opposite level, MSB first
  decoder.feed(std::span<const std::uint8_t>(&lead_in, 1), 1);
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

const BurstDecode& decode_whole_burst(const SharedBits& bits) {
  BurstDecodes& d = bits.decodes();
  // Only on a miss: receivers hold pointers to a decode made before.
  if (!d.whole) d.whole = run_decoder(*bits, bits->size(), 0);
  return *d.whole;
}

const BurstDecode& decode_burst_prefix(const SharedBits& bits, std::size_t cut_bit) {
  BurstDecodes& d = bits.decodes();
  for (const auto& [cut, decode] : d.prefixes) {
    if (cut == cut_bit) return *decode;
  }
  d.prefixes.emplace_back(cut_bit, run_decoder(*bits, std::min(cut_bit, bits->size()), 8));
  return *d.prefixes.back().second;
}

void seed_decode(const SharedBits& bits, const wire::EncodedFrame& where, std::uint8_t address,
                 std::span<const std::uint8_t> data, std::uint16_t fcs) {
  BurstDecodes& d = bits.decodes();
  if (d.whole || where.start_bit != 0 || where.end_bit != bits->size()) return;
  // A released object's decode, filled again (shared_bits.hpp, "Recycled"): every field
  // is set, the storage of its vectors kept.
  std::unique_ptr<BurstDecode> result =
      d.spare ? std::move(d.spare) : std::make_unique<BurstDecode>();
  seed_detail::fill_seed(*result, where, address, data, fcs);
  d.whole = std::move(result);
}

std::size_t burst_decode_count() { return decodes; }

}  // namespace sercon::chip

#include "sercon/chip/serial_unit_input.hpp"

#include <stdexcept>
#include <string>

#include "sercon/chip/line_edges.hpp"

namespace sercon::chip {
namespace {

constexpr sim::Time kIdleEdgeBits = 8;  // idle fill: one level change every 8 bit times

std::uint64_t ceil_div(sim::Time a, sim::Time b) {
  return static_cast<std::uint64_t>((a + b - 1) / b);
}

}  // namespace

void absorbed_out_of_order(std::string_view line, sim::Time last, sim::Time at) {
  throw std::logic_error(std::string(line) + ": a lazy burst at " + std::to_string(at) +
                         " ps is absorbed after a change at " + std::to_string(last) + " ps");
}

std::uint64_t edges_before(const RxdSegment& s, sim::Time t) {
  if (t <= s.since || !s.has_edges()) return 0;
  if (!s.is_burst) {
    const sim::Time spacing =
        s.condition == LineCondition::Idle ? kIdleEdgeBits * s.period : s.period;
    return ceil_div(t - s.since, spacing);
  }
  const auto in_bits = static_cast<std::size_t>(ceil_div(t - s.since, s.period));
  std::uint64_t edges = count_edges(*s.bits, in_bits);
  const sim::Time end = s.burst_end();
  if (t > end) edges += ceil_div(t - end, kIdleEdgeBits * s.period);
  return edges;
}

sim::Time nth_edge_time(const RxdSegment& s, std::uint64_t n) {
  if (!s.has_edges() || n == 0) throw std::logic_error("nth_edge_time: no such edge");
  const auto k = static_cast<sim::Time>(n - 1);
  if (!s.is_burst) {
    const sim::Time spacing =
        s.condition == LineCondition::Idle ? kIdleEdgeBits * s.period : s.period;
    return s.since + k * spacing;
  }
  const std::uint64_t in_bits = count_edges(*s.bits, s.bits->size());
  if (n <= in_bits) {
    return s.since +
           static_cast<sim::Time>(nth_edge_bit(*s.bits, static_cast<std::size_t>(n))) * s.period;
  }
  return s.burst_end() + static_cast<sim::Time>(n - in_bits - 1) * kIdleEdgeBits * s.period;
}

}  // namespace sercon::chip

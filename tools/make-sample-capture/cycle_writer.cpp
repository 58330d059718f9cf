#include "cycle_writer.hpp"

#include <stdexcept>
#include <string>
#include <vector>

#include "sercon/wire/fcs.hpp"

namespace sercon::sample {

CycleWriter::CycleWriter(unsigned bits_per_us, std::size_t lead_in_bits)
    : encoder_(true), bits_per_us_(bits_per_us), cycle_end_(lead_in_bits) {}

void CycleWriter::idle_until(std::size_t bit) {
  if (bit < encoder_.size()) {
    // The schedule is a constant of this program: overlapping telegrams are a bug in it.
    throw std::logic_error("telegram at bit " + std::to_string(bit) +
                           " overlaps the previous one (ends at bit " +
                           std::to_string(encoder_.size()) + ")");
  }
  encoder_.idle(bit - encoder_.size());
}

void CycleWriter::begin_cycle(unsigned cycle_us, std::uint8_t phase) {
  cycle_start_ = cycle_end_;
  cycle_end_ = cycle_start_ + std::size_t{cycle_us} * bits_per_us_;
  idle_until(cycle_start_);
  const std::uint8_t data[1] = {phase};
  mst_end_ = encoder_.telegram(255, data).end_bit;
}

void CycleWriter::send(unsigned t_us, std::uint8_t address, std::span<const std::uint8_t> data) {
  idle_until(mst_end_ + std::size_t{t_us} * bits_per_us_);
  encoder_.telegram(address, data);
}

void CycleWriter::send_corrupted(unsigned t_us, std::uint8_t address,
                                 std::span<const std::uint8_t> data) {
  idle_until(mst_end_ + std::size_t{t_us} * bits_per_us_);
  std::vector<std::uint8_t> body{address};
  body.insert(body.end(), data.begin(), data.end());
  const auto bad_fcs = static_cast<std::uint16_t>(~wire::fcs16(body));
  body.push_back(static_cast<std::uint8_t>(bad_fcs & 0xFF));  // FCS low byte first
  body.push_back(static_cast<std::uint8_t>(bad_fcs >> 8));
  encoder_.raw_frame(body);
}

wire::LineBits CycleWriter::finish(std::size_t tail_bits) {
  idle_until(cycle_end_ + tail_bits);
  return encoder_.take();
}

}  // namespace sercon::sample

#include "test_lines.hpp"

#include "sercon/wire/encoder.hpp"
#include "sercon/wire/fcs.hpp"

namespace sercon::testing {
namespace {

class LineBuilder {
 public:
  void idle(std::size_t bits) { encoder_.idle(bits); }

  void telegram(std::uint8_t address, std::vector<std::uint8_t> data, std::string kind,
                std::optional<unsigned> phase = std::nullopt) {
    const wire::EncodedFrame f = encoder_.telegram(address, data);
    frames_.push_back({f.start_bit, address, std::move(data), std::move(kind), phase, ""});
  }

  void mst(std::uint8_t byte) { telegram(255, {byte}, "MST", byte & 0x07U); }

  // A whole frame whose FCS is wrong.
  void bad_fcs(std::uint8_t address, std::vector<std::uint8_t> data, std::string kind) {
    std::vector<std::uint8_t> body{address};
    body.insert(body.end(), data.begin(), data.end());
    const auto fcs = static_cast<std::uint16_t>(wire::fcs16(body) ^ 0x0100);
    body.push_back(static_cast<std::uint8_t>(fcs & 0xFF));
    body.push_back(static_cast<std::uint8_t>(fcs >> 8));
    const wire::EncodedFrame f = encoder_.raw_frame(body);
    frames_.push_back({f.start_bit, address, std::move(data), std::move(kind), {}, "bad_fcs"});
  }

  void too_short(std::uint8_t address, std::uint8_t byte) {
    const std::vector<std::uint8_t> body{address, byte};
    const wire::EncodedFrame f = encoder_.raw_frame(body);
    frames_.push_back({f.start_bit, address, {byte}, "", {}, "too_short"});
  }

  // Flag, whole bytes, then seven 1s: the transmitter gave up.
  void abort(std::uint8_t address, std::vector<std::uint8_t> data) {
    const std::size_t start = encoder_.size();
    encoder_.flag();
    std::vector<std::uint8_t> bytes{address};
    bytes.insert(bytes.end(), data.begin(), data.end());
    encoder_.stuffed_bytes(bytes);
    encoder_.raw_decoded_bits("1111111");
    frames_.push_back({start, address, std::move(data), "", {}, "abort"});
  }

  // Flag, whole bytes, three stray bits, flag.
  void misaligned(std::uint8_t address, std::vector<std::uint8_t> data) {
    const std::size_t start = encoder_.size();
    encoder_.flag();
    std::vector<std::uint8_t> bytes{address};
    bytes.insert(bytes.end(), data.begin(), data.end());
    encoder_.stuffed_bytes(bytes);
    encoder_.raw_decoded_bits("010");
    encoder_.flag();
    frames_.push_back({start, address, std::move(data), "", {}, "misaligned"});
  }

  // Flag and whole bytes, then the capture ends.
  void truncated(std::uint8_t address, std::vector<std::uint8_t> data) {
    const std::size_t start = encoder_.size();
    encoder_.flag();
    std::vector<std::uint8_t> bytes{address};
    bytes.insert(bytes.end(), data.begin(), data.end());
    encoder_.stuffed_bytes(bytes);
    frames_.push_back({start, address, std::move(data), "", {}, "truncated"});
  }

  TestLine take() { return {encoder_.take(), std::move(frames_)}; }

 private:
  wire::LineEncoder encoder_;
  std::vector<ExpectedFrame> frames_;
};

}  // namespace

TestLine phase_walk_line() {
  LineBuilder b;
  b.idle(40);
  b.telegram(7, {0x01, 0x00, 0x00, 0x00}, "AT");  // before any MST
  b.idle(30);
  b.mst(0x00);
  b.idle(30);
  b.telegram(1, {0x00, 0x00, 0x00, 0x00}, "AT");
  b.idle(50);
  b.mst(0x01);
  b.idle(20);
  b.telegram(1, {0x01, 0x00, 0x00, 0x00}, "AT/MDT");
  b.idle(20);
  b.telegram(2, {0x01, 0x00, 0x00, 0x00}, "AT/MDT");
  b.idle(20);
  b.telegram(0, {0xAA, 0x55}, "ADDR0");
  b.idle(20);
  b.mst(0x02);
  b.idle(20);
  b.telegram(3, {0x0F, 0x00, 0x03, 0x00}, "AT/MDT");
  b.idle(20);
  b.mst(0x03);
  b.idle(20);
  b.telegram(4, {0x00, 0x40, 0x00, 0x00, 0x01, 0x02, 0x03, 0x04}, "AT");
  b.idle(20);
  std::vector<std::uint8_t> mdt;
  for (int i = 0; i < 32; ++i) mdt.push_back(static_cast<std::uint8_t>(0xF0 + i));
  b.telegram(255, mdt, "MDT");
  b.idle(20);
  b.mst(0x04);
  b.idle(20);
  b.telegram(254, {0xFF, 0xFF, 0xFF, 0xFF, 0x7E, 0x7E}, "AT");  // stuffing, flag-like data
  b.idle(20);
  b.mst(0x05);  // no such phase: shown, flagged invalid
  b.idle(20);
  b.telegram(1, {0x00, 0x00}, "AT");
  b.idle(20);
  b.mst(0x0C);  // phase = low 3 bits = 4
  b.idle(40);
  return b.take();
}

TestLine error_line() {
  LineBuilder b;
  b.idle(40);
  b.mst(0x04);
  b.idle(20);
  b.bad_fcs(3, {0x00, 0xC0, 0x00, 0x00, 0x11, 0x22, 0x33, 0x44}, "AT");
  b.idle(20);
  b.telegram(4, {0x00, 0xC0, 0x00, 0x00}, "AT");
  b.idle(20);
  b.abort(5, {0x10, 0x20});
  b.idle(20);
  b.too_short(6, 0x42);
  b.idle(20);
  b.misaligned(9, {0x10, 0x20, 0x30});
  b.idle(20);
  b.bad_fcs(255, {0x03}, "MST");
  b.idle(20);
  b.mst(0x04);
  b.idle(20);
  b.truncated(2, {0xAB, 0xCD, 0xEF});
  return b.take();
}

std::string hex(const std::vector<std::uint8_t>& bytes) {
  static constexpr char kDigits[] = "0123456789abcdef";
  std::string out;
  for (std::uint8_t b : bytes) {
    out += kDigits[b >> 4];
    out += kDigits[b & 0x0F];
  }
  return out;
}

}  // namespace sercon::testing

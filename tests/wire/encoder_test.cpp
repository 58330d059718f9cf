// Encoder: each line-coding rule of sercos-facts §1, checked on the line levels it writes.
#include "sercon/wire/encoder.hpp"

#include <gtest/gtest.h>

#include <iterator>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "sercon/wire/fcs.hpp"
#include "wire_test_util.hpp"

namespace sercon::wire {
namespace {

using test::decoded_string;
using test::levels_string;

// sercos-facts §1 (frame, LSB first, stuffing, NRZI, FCS vector FF 00 87 F0): the MST of
// CP0 worked out by hand, line starting high.
//   flag            0 1 1 1 1 1 1 0
//   FF  LSB first   1 1 1 1 1 [0] 1 1 1    a 0 is stuffed after five 1s
//   00              0 0 0 0 0 0 0 0        (the run of three 1s ends, no stuffing)
//   87 = 1000 0111  1 1 1 0 0 0 0 1        FCS low byte first
//   F0 = 1111 0000  0 0 0 0 1 1 1 1        four 1s: no stuffing before the flag
//   flag            0 1 1 1 1 1 1 0
// NRZI from level 1, a 0 flips the level, a 1 keeps it:
//   flag 00000001 | FF 111110000 | 00 10101010 | 87 00010100 | F0 10100000 | flag 11111110
TEST(Encoder, HandCheckedMstCp0) {
  LineEncoder enc(true);
  const std::vector<std::uint8_t> data = {0x00};
  const EncodedFrame f = enc.telegram(0xFF, data);
  EXPECT_EQ(levels_string(enc.bits()),
            "00000001"
            "111110000"
            "10101010"
            "00010100"
            "10100000"
            "11111110");
  EXPECT_EQ(f.start_bit, 0u);
  EXPECT_EQ(f.end_bit, 49u);
  EXPECT_FALSE(enc.level());
}

// sercos-facts §1: bit stuffing — after five consecutive 1s a 0 is inserted, also across
// byte boundaries and in the FCS; flags are never stuffed.
TEST(Encoder, StuffsAZeroAfterFiveOnes) {
  LineEncoder enc(false);
  const std::vector<std::uint8_t> bytes = {0x1F, 0xF8, 0xE0, 0x03};
  enc.stuffed_bytes(bytes);
  // 1F: 11111000 -> 11111 0 000; F8: 00011111 -> 00011111 0; E0 00000111 + 03 11000000:
  // 00000111 11 -> five 1s across the byte boundary -> 0 after them.
  EXPECT_EQ(decoded_string(enc.bits(), false),
            "111110000"
            "000111110"
            "00000111"
            "110000000");
  LineEncoder flags(false);
  flags.flag();
  EXPECT_EQ(decoded_string(flags.bits(), false), "01111110");  // six 1s stay unstuffed
}

// sercos-facts §1: the stuffing count carries over between stuffed_bytes calls (it is one
// run of data), and the count of 1s restarts after a 0 or a flag.
TEST(Encoder, StuffingRunCarriesAcrossCalls) {
  LineEncoder enc(true);
  const std::vector<std::uint8_t> first = {0xF0};   // ends in four 1s
  const std::vector<std::uint8_t> second = {0x01};  // starts with a 1: fifth 1
  enc.stuffed_bytes(first);
  enc.stuffed_bytes(second);
  EXPECT_EQ(decoded_string(enc.bits(), true),
            "00001111"
            "1"
            "0"
            "0000000");
}

// sercos-facts §1: NRZI — a 0 is a level change, a 1 keeps the level, from either level.
TEST(Encoder, NrziZeroChangesOneKeeps) {
  for (bool start : {false, true}) {
    LineEncoder enc(start);
    enc.raw_decoded_bits("0110100");
    // four 0s: four changes, so the line ends where it started
    EXPECT_EQ(levels_string(enc.bits()), start ? "0001101" : "1110010");
    EXPECT_EQ(decoded_string(enc.bits(), start), "0110100");
    EXPECT_EQ(enc.level(), start);
  }
  LineEncoder enc(true);
  enc.raw_decoded_bits(0b0110, 4);  // bit 0 first: 0 1 1 0
  EXPECT_EQ(decoded_string(enc.bits(), true), "0110");
  EXPECT_THROW(enc.raw_decoded_bits("01x"), std::invalid_argument);
  EXPECT_THROW(enc.raw_decoded_bits(0, 65), std::invalid_argument);
}

// sercos-facts §1: idle fill changes the line level once every 8 bit times and decodes to
// `0` then seven `1`s, repeated; here across many calls of odd sizes (the phase is kept).
TEST(Encoder, IdleFillHasAnEdgeEvery8BitsAcrossCalls) {
  LineEncoder enc(true);
  std::size_t total = 0;
  for (std::size_t n : {1u, 3u, 7u, 8u, 13u, 64u, 65u, 100u, 2u}) {
    enc.idle(n);
    total += n;
  }
  ASSERT_EQ(enc.size(), total);
  const std::string d = decoded_string(enc.bits(), true);
  for (std::size_t i = 0; i < d.size(); ++i) ASSERT_EQ(d[i], i % 8 == 0 ? '0' : '1') << i;
  const LineBits& b = enc.bits();
  bool prev = true;
  for (std::size_t i = 0; i < b.size(); ++i) {
    ASSERT_EQ(b[i] != prev, i % 8 == 0) << "edge only at multiples of 8, bit " << i;
    prev = b[i];
  }
}

// sercos-facts §1: frame = flag, address, data, FCS, flag — and the fill after a telegram
// restarts with its `0`, so the line keeps changing at least every 8 bits.
TEST(Encoder, FramePositionsAndFillAfterTelegram) {
  LineEncoder enc(true);
  enc.idle(5);
  const std::vector<std::uint8_t> data = {0x01};
  const EncodedFrame f = enc.telegram(0xFF, data);
  EXPECT_EQ(f.start_bit, 5u);
  EXPECT_EQ(f.end_bit, enc.size());
  enc.idle(16);
  const std::string d = decoded_string(enc.bits(), true);
  EXPECT_EQ(d.substr(f.start_bit, 8), "01111110");
  EXPECT_EQ(d.substr(f.end_bit - 8, 8), "01111110");
  EXPECT_EQ(d.substr(f.end_bit), "0111111101111111");
}

// Brief (LineEncoder::take): hands over the line; the encoder carries on at the same level.
TEST(Encoder, TakeKeepsTheLevel) {
  LineEncoder enc(false);
  enc.raw_decoded_bits("0");
  LineBits first = enc.take();
  EXPECT_EQ(levels_string(first), "1");
  EXPECT_EQ(enc.size(), 0u);
  enc.raw_decoded_bits("10");
  EXPECT_EQ(levels_string(enc.bits()), "10");
}

// sercos-facts §1 frame; brief: encode_stream puts fill before (at least 8 bits), between
// and after the telegrams.
TEST(Encoder, EncodeStreamLayout) {
  const std::vector<Telegram> ts = {{0xFF, {0x00}}, {0x01, {0x10, 0x20}}};
  const LineBits line = encode_stream(ts, 0, true);
  LineEncoder enc(true);
  enc.idle(8);
  enc.telegram(ts[0]);
  enc.telegram(ts[1]);
  EXPECT_EQ(line, enc.bits());
  const LineBits spaced = encode_stream(ts, 20, false);
  LineEncoder enc2(false);
  enc2.idle(20);
  enc2.telegram(ts[0]);
  enc2.idle(20);
  enc2.telegram(ts[1]);
  enc2.idle(20);
  EXPECT_EQ(spaced, enc2.bits());
}

}  // namespace
}  // namespace sercon::wire

namespace sercon::wire {
namespace {

// A telegram bit by bit, straight from sercos-facts §1 (flag, bytes LSB first with a 0
// stuffed after five 1s, FCS low byte first, flag; NRZI: a 0 changes the level).
LineBits reference_telegram(std::uint8_t address, const std::vector<std::uint8_t>& data,
                            bool level) {
  std::vector<bool> decoded;
  const auto flag = [&decoded] {
    for (int i = 0; i < 8; ++i) decoded.push_back(i != 0 && i != 7);
  };
  std::vector<std::uint8_t> bytes{address};
  bytes.insert(bytes.end(), data.begin(), data.end());
  Fcs16 fcs;
  fcs.update(bytes);
  bytes.push_back(static_cast<std::uint8_t>(fcs.value() & 0xFFu));
  bytes.push_back(static_cast<std::uint8_t>(fcs.value() >> 8));
  flag();
  int ones = 0;
  for (const std::uint8_t b : bytes) {
    for (int i = 0; i < 8; ++i) {
      const bool bit = ((b >> i) & 1u) != 0;
      decoded.push_back(bit);
      ones = bit ? ones + 1 : 0;
      if (ones == 5) {
        decoded.push_back(false);
        ones = 0;
      }
    }
  }
  flag();
  LineBits out;
  for (const bool bit : decoded) {
    if (!bit) level = !level;
    out.push_back(level);
  }
  return out;
}

// The encoder codes a byte with one table lookup and NRZI a word at a time (encoder.cpp):
// runs across byte and word boundaries and every carried-in run must come out as the
// bit-by-bit rules give.
TEST(Encoder, TelegramsMatchTheBitByBitRules) {
  std::mt19937 rng(0xC0DE);
  const std::uint8_t near_runs[] = {0xFF, 0x1F, 0xF8, 0x0F, 0xF0, 0x00, 0x7E, 0x3F, 0xFC, 0xEF};
  for (int n = 0; n < 4000; ++n) {
    std::vector<std::uint8_t> data(rng() % 48);
    for (std::uint8_t& b : data) {
      b = rng() % 3 == 0 ? near_runs[rng() % std::size(near_runs)]
                         : static_cast<std::uint8_t>(rng() & (rng() % 2 == 0 ? 0x77u : 0xFFu));
    }
    const auto address = static_cast<std::uint8_t>(rng());
    const bool level = (n & 1) != 0;
    LineEncoder enc(level);
    enc.telegram(address, data);
    ASSERT_EQ(levels_string(enc.bits()), levels_string(reference_telegram(address, data, level)))
        << "telegram " << n;
  }
}

// The three ways a telegram is coded give the bit-by-bit rules' bits: encode_telegram (a
// chip's send: a word filled from bit 0, stored at byte boundaries into a buffer used
// before, encoder.cpp), a fresh encoder (the same code), and an encoder after fill (its
// words built first bit highest and appended at any bit position).
TEST(Encoder, EveryCodingPathMatchesTheBitByBitRules) {
  std::mt19937 rng(0x5EED);
  LineBits reused;
  for (int n = 0; n < 3000; ++n) {
    std::vector<std::uint8_t> data(rng() % 200);
    for (std::uint8_t& b : data) {
      b = static_cast<std::uint8_t>(rng() % 4 == 0 ? 0xFF : rng() & (rng() % 2 ? 0xFFu : 0x3Fu));
    }
    const auto address = static_cast<std::uint8_t>(rng());
    const bool level = (n & 1) != 0;
    const std::string expected = levels_string(reference_telegram(address, data, level));

    const TelegramCoding c = encode_telegram(reused, level, address, data);
    ASSERT_EQ(levels_string(reused), expected) << "encode_telegram, telegram " << n;
    EXPECT_EQ(c.frame, (EncodedFrame{0, reused.size()}));
    EXPECT_EQ(c.level_after, reused[reused.size() - 1]);
    std::vector<std::uint8_t> with_address{address};
    with_address.insert(with_address.end(), data.begin(), data.end());
    EXPECT_EQ(c.fcs, fcs16(with_address));

    LineEncoder after_fill(level);
    after_fill.idle(1 + rng() % 70);
    const bool before = after_fill.level();
    const EncodedFrame f = after_fill.telegram(address, data);
    LineBits frame;
    for (std::size_t i = f.start_bit; i < f.end_bit; ++i) frame.push_back(after_fill.bits()[i]);
    ASSERT_EQ(levels_string(frame), levels_string(reference_telegram(address, data, before)))
        << "after fill, telegram " << n;
    EXPECT_EQ(f.end_bit, after_fill.size());
  }
}

// encode_telegram writes the buffer's bytes over rather than clearing them first
// (LineBits::drop_for_overwrite): after a longer telegram, the bytes past the new bits must
// be 0 again, as LineBits keeps them (appends or-in, word reads see past the last bit).
TEST(Encoder, EncodeTelegramOverALongerOneLeavesNothingPastItsBits) {
  std::mt19937 rng(0xB17E);
  LineBits reused;
  for (int n = 0; n < 2000; ++n) {
    std::vector<std::uint8_t> data(rng() % (n % 2 == 0 ? 200 : 8));
    for (std::uint8_t& b : data) b = static_cast<std::uint8_t>(rng() % 3 == 0 ? 0xFF : rng());
    const auto address = static_cast<std::uint8_t>(rng());
    const bool level = (n & 2) != 0;
    encode_telegram(reused, level, address, data);
    LineBits fresh;
    encode_telegram(fresh, level, address, data);
    ASSERT_EQ(reused, fresh) << "telegram " << n;
    LineBits grown = reused;  // the whole buffer, bytes past the bits too
    grown.append_run(false, 2500);
    fresh.append_run(false, 2500);
    ASSERT_EQ(grown, fresh) << "telegram " << n;
    ASSERT_EQ(reused.word_at(reused.size() - 1) << 1, 0u) << "telegram " << n;
  }
}

// Every byte value after every run of 1s carried into it (0..8 ended by a 0 before it, and
// longer after a byte of 1s), at every position in the encoder's 8-byte words, with 1s or 0s
// after it: the bit-by-bit rules' bits, on the word path and the byte path (encoder.cpp).
TEST(Encoder, EveryByteAfterEveryRunMatchesTheBitByBitRules) {
  LineBits reused;
  for (unsigned run = 0; run <= 8; ++run) {
    // The last `run` bits on the line (the high ones) 1s, the bit before them 0.
    const auto before = static_cast<std::uint8_t>((0xFFu << (8 - run)) & 0xFFu);
    for (unsigned value = 0; value < 256; ++value) {
      for (std::size_t at = 0; at < 9; ++at) {
        for (const std::uint8_t after : {std::uint8_t{0x00}, std::uint8_t{0xFF}}) {
          std::vector<std::uint8_t> data(at, 0x00);
          if (run > 5) data.push_back(0xFF);
          data.push_back(before);
          data.push_back(static_cast<std::uint8_t>(value));
          data.push_back(after);
          data.push_back(after);
          const bool level = (value & 1u) != 0;
          encode_telegram(reused, level, 0x00, data);
          ASSERT_EQ(levels_string(reused), levels_string(reference_telegram(0x00, data, level)))
              << "run " << run << " value " << value << " at " << at;
        }
      }
    }
  }
}

}  // namespace
}  // namespace sercon::wire

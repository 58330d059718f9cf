// Decoder: sercos-facts §1 read back from the line, the documented decisions (docs/wire.md),
// every error class produced deliberately, resynchronisation and chunked feeding.
#include "sercon/wire/decoder.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "sercon/wire/encoder.hpp"
#include "sercon/wire/fcs.hpp"
#include "wire_test_util.hpp"

namespace sercon::wire {
namespace {

using Bytes = std::vector<std::uint8_t>;

LineBits levels(const std::string& s) {
  LineBits b;
  for (char c : s) b.push_back(c == '1');
  return b;
}

Bytes with_fcs(Bytes body) {
  const std::uint16_t v = fcs16(body);
  body.push_back(static_cast<std::uint8_t>(v & 0xFF));
  body.push_back(static_cast<std::uint8_t>(v >> 8));
  return body;
}

void expect_same(const std::vector<DecodedFrame>& a, const std::vector<DecodedFrame>& b) {
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].start_bit, b[i].start_bit) << i;
    EXPECT_EQ(a[i].end_bit, b[i].end_bit) << i;
    EXPECT_EQ(a[i].address, b[i].address) << i;
    EXPECT_EQ(a[i].data, b[i].data) << i;
    EXPECT_EQ(a[i].fcs_received, b[i].fcs_received) << i;
    EXPECT_EQ(a[i].fcs_computed, b[i].fcs_computed) << i;
    EXPECT_EQ(a[i].error, b[i].error) << i;
  }
}

// sercos-facts §1, FCS vector FF 00 87 F0: the hand-worked line levels of the CP0 MST (see
// encoder_test.cpp), after one reference bit, decode to that telegram.
TEST(Decoder, DecodesHandCheckedMst) {
  const auto frames =
      decode_all(levels("1"
                        "00000001111110000101010100001010010100000"
                        "11111110"));
  ASSERT_EQ(frames.size(), 1u);
  EXPECT_EQ(frames[0].error, FrameError::None);
  EXPECT_EQ(frames[0].address, 0xFF);
  EXPECT_EQ(frames[0].data, Bytes{0x00});
  EXPECT_EQ(frames[0].fcs_received, 0xF087);
  EXPECT_EQ(frames[0].fcs_computed, 0xF087);
  EXPECT_EQ(frames[0].start_bit, 1u);
  EXPECT_EQ(frames[0].end_bit, 50u);
}

// Decision (docs/wire.md): line bit 0 is the level reference, so it decodes as 1 and a
// flag whose leading 0 would be bit 0 is not seen. The same line one bit later is.
TEST(Decoder, BitZeroIsTheLevelReference) {
  const std::string mst =
      "00000001111110000101010100001010010100000"
      "11111110";
  EXPECT_TRUE(decode_all(levels(mst)).empty());
  EXPECT_EQ(decode_all(levels("1" + mst)).size(), 1u);
}

// sercos-facts §1 (the whole line code): random telegrams of 1..250 data bytes, both
// initial levels, random fill (including none) decode to themselves at the encoder's
// positions.
TEST(Decoder, RoundTripRandomTelegrams) {
  for (std::uint64_t seed = 1; seed <= 40; ++seed) {
    std::mt19937_64 rng(seed);
    const bool level = (seed & 1) != 0;
    LineEncoder enc(level);
    enc.idle(8 + rng() % 20);
    std::vector<Telegram> sent;
    std::vector<EncodedFrame> where;
    for (int i = 0; i < 60; ++i) {
      sent.push_back(test::random_telegram(rng, 1, 250));
      where.push_back(enc.telegram(sent.back()));
      enc.idle(rng() % 4 == 0 ? 0 : rng() % 40);
    }
    const auto frames = decode_all(enc.bits());
    ASSERT_EQ(frames.size(), sent.size()) << "seed " << seed;
    for (std::size_t i = 0; i < sent.size(); ++i) {
      ASSERT_EQ(frames[i].error, FrameError::None) << "seed " << seed << " frame " << i;
      EXPECT_EQ(frames[i].address, sent[i].address);
      EXPECT_EQ(frames[i].data, sent[i].data);
      EXPECT_EQ(frames[i].start_bit, where[i].start_bit);
      EXPECT_EQ(frames[i].end_bit, where[i].end_bit);
    }
  }
}

// sercos-facts §1: all-ones and all-zeros data (most stuffing, most edges) round trip.
TEST(Decoder, RoundTripExtremeData) {
  for (std::uint8_t fill : {std::uint8_t{0x00}, std::uint8_t{0xFF}, std::uint8_t{0x7E},
                            std::uint8_t{0x1F}, std::uint8_t{0xF8}}) {
    const std::vector<Telegram> ts = {{fill, Bytes(1, fill)}, {fill, Bytes(250, fill)}};
    const auto frames = decode_all(encode_stream(ts, 3, true));
    ASSERT_EQ(frames.size(), 2u);
    for (std::size_t i = 0; i < 2; ++i) {
      EXPECT_EQ(frames[i].error, FrameError::None);
      EXPECT_EQ(frames[i].address, ts[i].address);
      EXPECT_EQ(frames[i].data, ts[i].data);
    }
  }
}

// sercos-facts §1: FCS over address + data; a wrong FCS is BadFcs with both values
// reported, and the next telegram decodes.
TEST(Decoder, BadFcsThenResync) {
  LineEncoder enc(true);
  enc.idle(8);
  const EncodedFrame bad = enc.raw_frame(Bytes{0xFF, 0x00, 0x87, 0xF1});
  enc.telegram(0x05, Bytes{1, 2, 3});
  enc.idle(8);
  const auto frames = decode_all(enc.bits());
  ASSERT_EQ(frames.size(), 2u);
  EXPECT_EQ(frames[0].error, FrameError::BadFcs);
  EXPECT_EQ(frames[0].fcs_received, 0xF187);
  EXPECT_EQ(frames[0].fcs_computed, 0xF087);
  EXPECT_EQ(frames[0].address, 0xFF);
  EXPECT_EQ(frames[0].data, Bytes{0x00});
  EXPECT_EQ(frames[0].start_bit, bad.start_bit);
  EXPECT_EQ(frames[0].end_bit, bad.end_bit);
  EXPECT_TRUE(frames[1].ok());
  EXPECT_EQ(frames[1].data, (Bytes{1, 2, 3}));
}

// sercos-facts §1: seven or more 1s cannot occur inside a frame: Abort at the seventh 1,
// then the decoder hunts for the next flag.
TEST(Decoder, AbortThenResync) {
  LineEncoder enc(false);
  enc.idle(8);
  enc.flag();
  enc.stuffed_bytes(Bytes{0x12, 0x34, 0x56});
  const std::size_t before_ones = enc.size();
  enc.raw_decoded_bits("1111111111");
  enc.idle(20);
  enc.telegram(0x07, Bytes{9, 9});
  const auto frames = decode_all(enc.bits());
  ASSERT_EQ(frames.size(), 2u);
  EXPECT_EQ(frames[0].error, FrameError::Abort);
  EXPECT_EQ(frames[0].start_bit, 8u);
  EXPECT_EQ(frames[0].end_bit, before_ones + 7);  // where the seventh 1 was seen
  EXPECT_EQ(frames[0].address, 0x12);
  EXPECT_EQ(frames[0].data, (Bytes{0x34, 0x56}));
  EXPECT_TRUE(frames[1].ok());
  EXPECT_EQ(frames[1].address, 0x07);
}

// Decision (docs/wire.md): the minimum frame is address + 1 data byte + FCS = 4 bytes;
// 1..3 whole bytes are TooShort, with the bytes kept; then resync.
TEST(Decoder, TooShortThenResync) {
  LineEncoder enc(true);
  enc.idle(8);
  enc.raw_frame(Bytes{0xFF, 0x87, 0xF0});
  enc.raw_frame(Bytes{0x42});
  enc.telegram(0x01, Bytes{0xAA});
  const auto frames = decode_all(enc.bits());
  ASSERT_EQ(frames.size(), 3u);
  EXPECT_EQ(frames[0].error, FrameError::TooShort);
  EXPECT_EQ(frames[0].address, 0xFF);
  EXPECT_EQ(frames[0].data, (Bytes{0x87, 0xF0}));
  EXPECT_EQ(frames[1].error, FrameError::TooShort);
  EXPECT_EQ(frames[1].address, 0x42);
  EXPECT_TRUE(frames[1].data.empty());
  EXPECT_TRUE(frames[2].ok());
}

// Decision (docs/wire.md): bits between flags that are not whole bytes are Misaligned
// (the frame is not an FCS candidate); then resync.
TEST(Decoder, MisalignedThenResync) {
  LineEncoder enc(true);
  enc.idle(8);
  enc.flag();
  enc.stuffed_bytes(with_fcs({0xFF, 0x00}));
  enc.raw_decoded_bits("010");
  enc.flag();
  enc.telegram(0x02, Bytes{0x10, 0x20});
  const auto frames = decode_all(enc.bits());
  ASSERT_EQ(frames.size(), 2u);
  EXPECT_EQ(frames[0].error, FrameError::Misaligned);
  EXPECT_EQ(frames[0].address, 0xFF);
  EXPECT_EQ(frames[0].data, (Bytes{0x00, 0x87, 0xF0}));
  EXPECT_TRUE(frames[1].ok());
  EXPECT_EQ(frames[1].address, 0x02);
}

// Brief: finish() reports a frame still open as Truncated, ending where the input did;
// afterwards the decoder starts over.
TEST(Decoder, TruncatedAtFinishThenStartsOver) {
  LineEncoder enc(true);
  enc.idle(8);
  enc.telegram(0x03, Bytes{1});
  enc.flag();
  enc.stuffed_bytes(Bytes{0x11, 0x22});
  std::vector<DecodedFrame> frames;
  LineDecoder dec([&](const DecodedFrame& f) { frames.push_back(f); });
  dec.feed(enc.bits());
  ASSERT_EQ(frames.size(), 1u);
  dec.finish();
  ASSERT_EQ(frames.size(), 2u);
  EXPECT_EQ(frames[1].error, FrameError::Truncated);
  EXPECT_EQ(frames[1].end_bit, enc.size());
  EXPECT_EQ(frames[1].address, 0x11);
  EXPECT_EQ(frames[1].data, Bytes{0x22});
  EXPECT_EQ(dec.position(), 0u);
  dec.feed(enc.bits());  // the same line again: same positions
  dec.finish();
  ASSERT_EQ(frames.size(), 4u);
  EXPECT_EQ(frames[2].start_bit, frames[0].start_bit);
  EXPECT_EQ(frames[3].error, FrameError::Truncated);
}

// Decision (docs/wire.md): fewer than 8 bits after a flag, then fill, an abort, another
// flag or the end of input, is inter-frame fill: no frame and no error.
TEST(Decoder, ShortRemnantsAfterAFlagAreFill) {
  LineEncoder enc(true);
  enc.idle(8);
  enc.flag();
  enc.raw_decoded_bits("0101");
  enc.idle(16);  // ends in seven 1s: an abort of 5 bits
  enc.flag();
  enc.flag();
  enc.flag();  // back-to-back flags
  enc.raw_decoded_bits("0100101");
  enc.flag();  // 7 bits between flags
  enc.raw_decoded_bits("10");
  const auto frames = decode_all(enc.bits());  // ends 2 bits after a flag
  EXPECT_TRUE(frames.empty());
}

// sercos-facts §1: fill between telegrams — and a flag may share its 0 with the previous
// one (0111111011111110); both telegrams decode, the second starting on the shared 0.
TEST(Decoder, SharedZeroFlags) {
  LineEncoder enc(true);
  enc.idle(8);
  enc.flag();
  enc.stuffed_bytes(with_fcs({0x01, 0x02}));
  enc.raw_decoded_bits("011111101111110");
  enc.stuffed_bytes(with_fcs({0x03, 0x04}));
  enc.flag();
  const auto frames = decode_all(enc.bits());
  ASSERT_EQ(frames.size(), 2u);
  EXPECT_TRUE(frames[0].ok());
  EXPECT_TRUE(frames[1].ok());
  EXPECT_EQ(frames[0].address, 0x01);
  EXPECT_EQ(frames[1].address, 0x03);
  EXPECT_EQ(frames[1].start_bit + 1, frames[0].end_bit);
}

// decoder.hpp: the frame a sink gets stays valid for the whole call, even when the sink
// runs another decoder meanwhile (only calling back into the same decoder is excluded).
TEST(Decoder, FrameStaysValidWhileASinkDecodesAnotherLine) {
  LineEncoder outer_enc(true);
  outer_enc.idle(8);
  outer_enc.telegram(0x05, Bytes{1, 2, 3, 4});
  LineEncoder inner_enc(true);
  inner_enc.idle(8);
  inner_enc.telegram(0x06, Bytes{9, 8});
  std::vector<DecodedFrame> outer;
  std::vector<DecodedFrame> inner;
  LineDecoder dec([&](const DecodedFrame& f) {
    const DecodedFrame before = f;
    inner = decode_all(inner_enc.bits());
    expect_same({before}, {f});
    outer.push_back(f);
  });
  dec.feed(outer_enc.bits());
  dec.finish();
  ASSERT_EQ(outer.size(), 1u);
  EXPECT_EQ(outer[0].address, 0x05);
  EXPECT_EQ(outer[0].data, (Bytes{1, 2, 3, 4}));
  ASSERT_EQ(inner.size(), 1u);
  EXPECT_EQ(inner[0].address, 0x06);
  EXPECT_EQ(inner[0].data, (Bytes{9, 8}));
}

// A mixed stream with every error class, fed whole, in random LineBits chunks and as
// random packed-byte chunks: identical frames at identical global positions.
TEST(Decoder, ChunkedFeedingEqualsWholeFeeding) {
  std::mt19937_64 rng(99);
  LineEncoder enc(false);
  enc.idle(9);
  for (int i = 0; i < 80; ++i) {
    switch (rng() % 6) {
      case 0:
        enc.raw_frame(Bytes{0xFF, 0x00, 0x00, 0x00});
        break;  // BadFcs
      case 1:
        enc.flag();
        enc.stuffed_bytes(Bytes{1, 2, 3});
        enc.raw_decoded_bits("1111111");
        break;
      case 2:
        enc.raw_frame(Bytes{0x10, 0x20});
        break;  // TooShort
      case 3:
        enc.flag();
        enc.stuffed_bytes(Bytes{5, 6, 7, 8});
        enc.raw_decoded_bits("01");
        enc.flag();
        break;
      default:
        enc.telegram(test::random_telegram(rng, 1, 60));
        break;
    }
    enc.idle(rng() % 30);
  }
  enc.flag();
  enc.stuffed_bytes(Bytes{0xAB, 0xCD});  // Truncated at the end
  const LineBits& line = enc.bits();
  const auto whole = decode_all(line);
  ASSERT_GT(whole.size(), 60u);

  for (int round = 0; round < 30; ++round) {
    std::vector<DecodedFrame> a;
    std::vector<DecodedFrame> b;
    LineDecoder da([&](const DecodedFrame& f) { a.push_back(f); });
    LineDecoder db([&](const DecodedFrame& f) { b.push_back(f); });
    std::size_t i = 0;
    while (i < line.size()) {
      const std::size_t n = std::min<std::size_t>(line.size() - i, rng() % 200);
      LineBits chunk;
      for (std::size_t k = 0; k < n; ++k) chunk.push_back(line[i + k]);
      da.feed(chunk);
      db.feed(chunk.packed(), chunk.size());
      i += n;
    }
    EXPECT_EQ(da.position(), line.size());
    da.finish();
    db.finish();
    expect_same(whole, a);
    expect_same(whole, b);
  }
}

// Brief (bad input never UB; decoder invariants): random line noise never throws, frames
// are in order and inside the input, and a frame without error has a matching FCS.
TEST(Decoder, RandomNoiseKeepsInvariants) {
  std::mt19937_64 rng(7);
  for (int round = 0; round < 50; ++round) {
    LineBits line;
    const std::size_t n = 1000 + rng() % 20000;
    // Mostly few edges (long runs) so flags and frames do appear.
    bool level = false;
    while (line.size() < n) {
      line.append_run(level, 1 + rng() % 8);
      level = !level;
    }
    const auto frames = decode_all(line);
    std::size_t last_start = 0;
    for (const auto& f : frames) {
      EXPECT_GE(f.start_bit, last_start);
      EXPECT_LT(f.start_bit, f.end_bit);
      EXPECT_LE(f.end_bit, line.size());
      if (f.ok()) {
        EXPECT_EQ(f.fcs_received, f.fcs_computed);
      }
      last_start = f.start_bit;
    }
  }
}

// Brief (bad input gets exceptions): packed bytes too few for the bit count, empty sink.
TEST(Decoder, RejectsBadInput) {
  LineDecoder dec([](const DecodedFrame&) {});
  const Bytes two = {0, 0};
  EXPECT_THROW(dec.feed(two, 17), std::invalid_argument);
  EXPECT_NO_THROW(dec.feed(two, 16));
  EXPECT_THROW(LineDecoder(LineDecoder::Sink{}), std::invalid_argument);
}

// Brief (FrameError with to_string): every error class has a readable name.
TEST(Decoder, ErrorNames) {
  EXPECT_EQ(to_string(FrameError::None), "none");
  EXPECT_EQ(to_string(FrameError::BadFcs), "bad FCS");
  for (FrameError e :
       {FrameError::Abort, FrameError::TooShort, FrameError::Misaligned, FrameError::Truncated})
    EXPECT_FALSE(to_string(e).empty());
}

}  // namespace
}  // namespace sercon::wire

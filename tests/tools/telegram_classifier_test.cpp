// Requirement: kinds from address, length and the phase of the last good MST
// (docs/decode.md "Kinds"; sercos-facts §1 addresses, §2 telegrams): MST = 255 with one
// byte, MDT = 255 longer, AT/MDT = 1..254 in CP1/CP2, AT otherwise, ADDR0 = address 0.
#include "telegram_classifier.hpp"

#include <gtest/gtest.h>

namespace sercon::tools {
namespace {

wire::DecodedFrame frame(std::uint8_t address, std::vector<std::uint8_t> data,
                         wire::FrameError error = wire::FrameError::None) {
  wire::DecodedFrame f;
  f.address = address;
  f.data = std::move(data);
  f.error = error;
  return f;
}

TEST(TelegramClassifier, BroadcastKindsByLength) {
  TelegramClassifier c;
  EXPECT_EQ(c.classify(frame(255, {0x00}), 0).kind, TelegramKind::Mst);
  EXPECT_EQ(c.classify(frame(255, {0x00, 0x01}), 0).kind, TelegramKind::Mdt);
  EXPECT_EQ(c.classify(frame(255, std::vector<std::uint8_t>(32, 0)), 0).kind, TelegramKind::Mdt);
}

TEST(TelegramClassifier, AddressedTelegramsDependOnThePhase) {
  TelegramClassifier c;
  EXPECT_EQ(c.classify(frame(5, {1, 2}), 0).kind, TelegramKind::At);  // before any MST
  for (std::uint8_t phase = 0; phase <= 7; ++phase) {
    c.classify(frame(255, {phase}), 0);
    const TelegramKind expected =
        phase == 1 || phase == 2 ? TelegramKind::AtOrMdt : TelegramKind::At;
    EXPECT_EQ(c.classify(frame(1, {1, 0, 0, 0}), 0).kind, expected) << int{phase};
    EXPECT_EQ(c.classify(frame(254, {1, 0}), 0).kind, expected) << int{phase};
  }
}

TEST(TelegramClassifier, AddressZeroIsNoStation) {
  TelegramClassifier c;
  c.classify(frame(255, {0x01}), 0);
  EXPECT_EQ(c.classify(frame(0, {1, 2}), 0).kind, TelegramKind::NoStation);
}

TEST(TelegramClassifier, PhaseIsTheLowThreeBitsAndAboveFourIsInvalid) {
  TelegramClassifier c;
  const TelegramRow cp4 = c.classify(frame(255, {0x8C}), 0);
  EXPECT_EQ(cp4.phase, 4U);
  EXPECT_TRUE(cp4.phase_valid());
  const TelegramRow cp6 = c.classify(frame(255, {0x06}), 0);
  EXPECT_EQ(cp6.phase, 6U);
  EXPECT_FALSE(cp6.phase_valid());
  EXPECT_EQ(c.phase(), 6U);
}

TEST(TelegramClassifier, OnlyAGoodMstChangesThePhase) {
  TelegramClassifier c;
  c.classify(frame(255, {0x01}), 0);
  const TelegramRow bad = c.classify(frame(255, {0x03}, wire::FrameError::BadFcs), 0);
  EXPECT_EQ(bad.kind, TelegramKind::Mst);
  EXPECT_EQ(bad.fcs_ok, false);
  EXPECT_EQ(bad.error, ErrorClass::BadFcs);
  EXPECT_EQ(c.phase(), 1U);
}

TEST(TelegramClassifier, BrokenFramesHaveNoKind) {
  TelegramClassifier c;
  const std::pair<wire::FrameError, ErrorClass> cases[] = {
      {wire::FrameError::Abort, ErrorClass::Abort},
      {wire::FrameError::TooShort, ErrorClass::TooShort},
      {wire::FrameError::Misaligned, ErrorClass::Misaligned},
      {wire::FrameError::Truncated, ErrorClass::Truncated}};
  for (const auto& [error, expected] : cases) {
    const TelegramRow row = c.classify(frame(255, {0x02}, error), 1234);
    EXPECT_FALSE(row.kind.has_value());
    EXPECT_FALSE(row.fcs_ok.has_value());
    EXPECT_EQ(row.error, expected);
    EXPECT_EQ(row.t_ps, 1234);
  }
  EXPECT_FALSE(c.phase().has_value());
}

}  // namespace
}  // namespace sercon::tools

// Requirement: the summary counts telegrams by kind and errors by class and lists the
// phases seen in order (issue "sercon decode", text output).
#include "decode_summary.hpp"

#include <gtest/gtest.h>

namespace sercon::tools {
namespace {

TelegramRow good(TelegramKind kind, std::optional<unsigned> phase = std::nullopt) {
  TelegramRow row;
  row.kind = kind;
  row.fcs_ok = true;
  row.phase = phase;
  return row;
}

TelegramRow broken(ErrorClass error) {
  TelegramRow row;
  row.error = error;
  return row;
}

TEST(DecodeSummary, CountsByKindAndClass) {
  DecodeSummary s;
  s.add(good(TelegramKind::Mst, 0));
  s.add(good(TelegramKind::At));
  s.add(good(TelegramKind::At));
  s.add(good(TelegramKind::NoStation));
  s.add(broken(ErrorClass::BadFcs));
  s.add(broken(ErrorClass::Truncated));
  EXPECT_EQ(s.telegrams(), 4U);
  EXPECT_EQ(s.telegrams(TelegramKind::At), 2U);
  EXPECT_EQ(s.telegrams(TelegramKind::Mdt), 0U);
  EXPECT_EQ(s.errors(), 2U);
  EXPECT_EQ(s.errors(ErrorClass::BadFcs), 1U);
  EXPECT_EQ(s.errors(ErrorClass::Abort), 0U);
}

TEST(DecodeSummary, PhasesInOrderWithoutRepeats) {
  DecodeSummary s;
  for (unsigned p : {0U, 0U, 1U, 1U, 2U, 1U, 2U, 3U, 4U, 7U, 4U, 4U})
    s.add(good(TelegramKind::Mst, p));
  EXPECT_EQ(s.phases(), (std::vector<unsigned>{0, 1, 2, 1, 2, 3, 4, 7, 4}));
  EXPECT_EQ(s.invalid_phase_msts(), 1U);
}

}  // namespace
}  // namespace sercon::tools

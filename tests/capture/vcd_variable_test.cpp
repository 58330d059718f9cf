// Requirement: `--signal` picks a VCD signal by reference or scope.name; without it the
// only 1-bit signal; errors list the candidates (issue "capture readers", VCD).
#include "sercon/capture/vcd_variable.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "sercon/capture/capture_error.hpp"

namespace sercon::capture {
namespace {

VcdVariable var(std::string type, std::uint32_t width, std::string id, std::string ref,
                std::string scope) {
  return VcdVariable{std::move(type), width, std::move(id), std::move(ref), std::move(scope)};
}

std::string error_of(const std::vector<VcdVariable>& vars, std::string_view wanted) {
  try {
    select_vcd_variable(vars, wanted);
  } catch (const CaptureError& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(VcdVariable, FullNameJoinsScopes) {
  EXPECT_EQ(var("wire", 1, "!", "rx", "top.phy").full_name(), "top.phy.rx");
  EXPECT_EQ(var("wire", 1, "!", "rx", "").full_name(), "rx");
}

TEST(VcdVariable, DefaultIsTheOnlyOneBitSignal) {
  const std::vector<VcdVariable> vars{
      var("wire", 8, "#", "bus", "top"), var("reg", 1, "!", "rx", "top"),
      var("real", 1, "$", "analog", "top"), var("event", 1, "%", "tick", "top")};
  EXPECT_EQ(select_vcd_variable(vars, "").id, "!");
}

TEST(VcdVariable, AliasesOfOneIdentifierAreOneSignal) {
  const std::vector<VcdVariable> vars{var("wire", 1, "!", "rx", "top"),
                                      var("wire", 1, "!", "rx_in", "top.phy")};
  EXPECT_EQ(select_vcd_variable(vars, "").id, "!");
}

TEST(VcdVariable, SeveralOneBitSignalsNeedSignalAndAreListed) {
  const std::vector<VcdVariable> vars{var("wire", 1, "!", "rx", "top"),
                                      var("wire", 1, "\"", "tx", "top")};
  const std::string message = error_of(vars, "");
  EXPECT_NE(message.find("several 1-bit signals: top.rx, top.tx"), std::string::npos) << message;
  EXPECT_NE(message.find("--signal"), std::string::npos) << message;
}

// Brief ("bad input gets a clear error"): a file with thousands of signals and no --signal
// gets an error of a line or two: the first 16 names and how many more, not all of them.
TEST(VcdVariable, AListOfThousandsOfSignalsIsCutShort) {
  std::vector<VcdVariable> vars;
  for (int i = 0; i < 20'000; ++i) {
    const std::string n = std::to_string(i);
    vars.push_back(var("wire", 1, std::string("id").append(n), std::string("s").append(n), "t"));
  }
  const std::string e = error_of(vars, "");
  EXPECT_NE(e.find("t.s0, t.s1"), std::string::npos) << e;
  EXPECT_NE(e.find("t.s15 and 19984 more; choose one with --signal NAME"), std::string::npos) << e;
  EXPECT_LT(e.size(), 400u);
}

TEST(VcdVariable, NoOneBitSignalListsWhatThereIs) {
  const std::vector<VcdVariable> vars{var("wire", 8, "#", "bus", "top")};
  const std::string message = error_of(vars, "");
  EXPECT_NE(message.find("no 1-bit signal"), std::string::npos) << message;
  EXPECT_NE(message.find("top.bus (8 bits)"), std::string::npos) << message;
}

TEST(VcdVariable, SelectByReferenceOrFullName) {
  const std::vector<VcdVariable> vars{var("wire", 1, "!", "rx", "top.a"),
                                      var("wire", 1, "\"", "tx", "top.b")};
  EXPECT_EQ(select_vcd_variable(vars, "tx").id, "\"");
  EXPECT_EQ(select_vcd_variable(vars, "top.a.rx").id, "!");
}

TEST(VcdVariable, AReferenceInTwoScopesIsAmbiguous) {
  const std::vector<VcdVariable> vars{var("wire", 1, "!", "rx", "top.a"),
                                      var("wire", 1, "\"", "rx", "top.b")};
  const std::string message = error_of(vars, "rx");
  EXPECT_NE(message.find("top.a.rx, top.b.rx"), std::string::npos) << message;
  EXPECT_EQ(select_vcd_variable(vars, "top.b.rx").id, "\"");
}

TEST(VcdVariable, UnknownNameListsTheCandidates) {
  const std::vector<VcdVariable> vars{var("wire", 1, "!", "rx", "top")};
  const std::string message = error_of(vars, "fibre");
  EXPECT_NE(message.find("no signal named 'fibre'"), std::string::npos) << message;
  EXPECT_NE(message.find("top.rx"), std::string::npos) << message;
}

TEST(VcdVariable, AWideSignalCannotBeDecoded) {
  const std::vector<VcdVariable> vars{var("wire", 8, "#", "bus", "top"),
                                      var("wire", 1, "!", "rx", "top")};
  const std::string message = error_of(vars, "bus");
  EXPECT_NE(message.find("8-bit wire"), std::string::npos) << message;
}

}  // namespace
}  // namespace sercon::capture

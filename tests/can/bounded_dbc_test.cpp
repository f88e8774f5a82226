// A DBC's cost is bounded whatever its text. A valid file of 2 MB can give one message 45,000
// multiplexed signals; each statement naming a signal searched the message's signals one by
// one and the overlap check compared every pair: 71 s to load, past vmassd's 30 s start limit.
// Now a message holds at most 4096 signals (the next are left out with an error at their line),
// names are found in an index, an SG_MUL_VAL_ takes at most 1024 ranges, and the overlap check
// stops (with a warning at the signal where it stopped) past a fixed amount of work.
#include <gtest/gtest.h>

#include <string>

#include "vmass/can/dbc.hpp"

namespace vmass::can {
namespace {

/// One message: a switch and `count` signals multiplexed by it, all on the same bits, each with
/// a VAL_ table and an SG_MUL_VAL_ of `ranges` ranges.
std::string big_multiplexed_dbc(int count, int ranges = 1) {
  std::string t = "VERSION \"\"\nNS_ :\nBS_:\nBU_: ECU\nBO_ 256 BIG: 8 ECU\n";
  t += " SG_ Switch M : 0|16@1+ (1,0) [0|65535] \"\" ECU\n";
  for (int i = 0; i < count; ++i) {
    t += " SG_ S" + std::to_string(i) + " m" + std::to_string(i % 60000) +
         " : 16|16@1+ (1,0) [0|0] \"\" ECU\n";
  }
  for (int i = 0; i < count; ++i) {
    t += "VAL_ 256 S" + std::to_string(i) + " 0 \"zero\" 1 \"one\" ;\n";
  }
  for (int i = 0; i < count; ++i) {
    t += "SG_MUL_VAL_ 256 S" + std::to_string(i) + " Switch ";
    for (int k = 0; k < ranges; ++k) {
      const std::string v = std::to_string((i * ranges + k) % 65536);
      t += (k ? ", " : "") + v + "-" + v;
    }
    t += ";\n";
  }
  return t;
}

int count_containing(const DbcParseResult& r, const std::string& what) {
  int n = 0;
  for (const DbcDiagnostic& d : r.diagnostics) n += d.message.find(what) != std::string::npos;
  return n;
}

TEST(BoundedDbc, AMessageKeepsAtMost4096SignalsAndSaysWhereTheRestBegin) {
  const DbcParseResult r = parse_dbc(big_multiplexed_dbc(45000), "big.dbc");
  ASSERT_EQ(r.database.messages.size(), 1u);
  EXPECT_EQ(r.database.messages[0].signals.size(), 4096u);
  EXPECT_FALSE(r.ok());
  // The first signal left out is the 4097th (S4095: the switch is the first), at its line.
  bool located = false;
  for (const DbcDiagnostic& d : r.diagnostics) {
    if (d.message.find("more than 4096 signals") == std::string::npos) continue;
    EXPECT_NE(d.message.find("S4095"), std::string::npos) << d.message;
    EXPECT_EQ(d.line, 4102) << d.message;  // five header lines, the switch, S0..S4094
    located = true;
    break;
  }
  EXPECT_TRUE(located);
  EXPECT_EQ(count_containing(r, "more than 4096 signals"), 1);  // one error, not 40,904
}

TEST(BoundedDbc, TheOverlapCheckStopsPastItsWorkAndSaysSo) {
  // 4096 signals in the message, every two on the same bits and each selected by 16 values:
  // the pairwise check would make 2 billion range comparisons; it stops at its bound, with a
  // warning. With one value each (8 million pairs) it runs to the end.
  EXPECT_EQ(count_containing(parse_dbc(big_multiplexed_dbc(4095), "one.dbc"), "not checked"), 0);
  const DbcParseResult r = parse_dbc(big_multiplexed_dbc(4095, 16), "pairs.dbc");
  ASSERT_EQ(r.database.messages.size(), 1u);
  EXPECT_EQ(r.database.messages[0].signals.size(), 4096u);
  EXPECT_EQ(count_containing(r, "overlaps not checked"), 1);
  EXPECT_EQ(count_containing(r, "more than 4096 signals"), 0);
}

TEST(BoundedDbc, AnSgMulValOfMoreThan1024RangesIsAnError) {
  std::string t = "VERSION \"\"\nNS_ :\nBS_:\nBU_: ECU\nBO_ 256 M: 8 ECU\n";
  t += " SG_ Switch M : 0|16@1+ (1,0) [0|65535] \"\" ECU\n";
  t += " SG_ A m1 : 16|16@1+ (1,0) [0|0] \"\" ECU\n";
  t += "SG_MUL_VAL_ 256 A Switch ";
  for (int i = 0; i < 1100; ++i) t += (i ? ", " : "") + std::to_string(i) + "-" + std::to_string(i);
  t += ";\n";
  const DbcParseResult r = parse_dbc(t, "ranges.dbc");
  EXPECT_EQ(count_containing(r, "more than 1024 ranges"), 1);
}

}  // namespace
}  // namespace vmass::can

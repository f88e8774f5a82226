// DBC files from many hands (issue 11): the parser recovers at the next statement and reports
// every error with its line; binary data, empty files and absurd tokens are refused with one
// bounded message; a lone lowercase `m` is the switch `M`; factor 0, minimum above maximum,
// duplicate message names, multiplexer values the switch cannot hold and declared ranges the
// bits cannot carry are reported. Expected diagnostics are written out by hand.
#include <gtest/gtest.h>

#include <cstdint>
#include <string>

#include "vmass/can/dbc.hpp"
#include "vmass/can/decoder.hpp"

namespace vmass::can {
namespace {

std::string dump(const DbcParseResult& r) {
  std::string s;
  for (const auto& d : r.diagnostics) s += d.to_string() + "\n";
  return s;
}

std::vector<std::string> lines(const DbcParseResult& r) {
  std::vector<std::string> out;
  for (const auto& d : r.diagnostics) out.push_back(d.to_string());
  return out;
}

TEST(DbcManyHands, EveryBrokenStatementIsReportedAndTheRestLoads) {
  const DbcParseResult r = parse_dbc(R"(VERSION ""
BO_ 100 A: 8 ECU
 SG_ Good1 : 0|8@1+ (1,0) [0|0] "" ECU
 SG_ Bad1 : 8|8@2+ (1,0) [0|0] "" ECU
 SG_ Good2 : 16|8@1+ (1,0) [0|0] "" ECU
BO_ 200 B 8 ECU
 SG_ Skipped : 0|8@1+ (1,0) [0|0] "" ECU
BO_ 300 C: 8 ECU
 SG_ Good3 : 0|8@1+ (1,0) [0|0] "" ECU
BA_DEF_ BO_ "GenMsgCycleTime" INT 0 10000;
BA_ "GenMsgCycleTime" BO_ 300 20;
CM_ SG_ 300 Good3 "never closed
BO_ 400 D: 8 ECU
)",
                                     "f.dbc");
  EXPECT_EQ(lines(r), (std::vector<std::string>{
                          "f.dbc:4:17: error: expected byte order 0 (Motorola) or 1 (Intel) after "
                          "'@', found '2+ (1,0) [0|0] \"\" EC'",
                          "f.dbc:6:11: error: expected ':' after the message name, found '8 ECU'",
                          "f.dbc:12:19: error: string opened here is never closed"}))
      << dump(r);
  ASSERT_EQ(r.database.messages.size(), 3u);  // A, C and D; B's signal is skipped with it
  EXPECT_EQ(r.database.messages[0].signals.size(), 2u);
  EXPECT_EQ(r.database.messages[1].name, "C");
  EXPECT_EQ(r.database.messages[1].cycle_time_ms, 20);  // read after the broken statements
  // A string may span lines, so a missing quote takes everything up to the next quote (here:
  // none): the parse goes on from the line after the opening quote.
  EXPECT_EQ(r.database.messages[2].name, "D");
}

TEST(DbcManyHands, ParsingStopsAfterAHundredErrors) {
  std::string text = "BO_ 1 A: 8 E\n";
  for (int i = 0; i < 150; ++i)
    text += " SG_ S" + std::to_string(i) + " : 0|8@9+ (1,0) [0|0] \"\" E\n";
  const DbcParseResult r = parse_dbc(text, "many.dbc");
  EXPECT_EQ(r.error_count(), 101) << dump(r);
  EXPECT_EQ(r.diagnostics.back().message,
            "too many errors (100); the rest of the file is not read");
}

TEST(DbcManyHands, BinaryDataAndEmptyFilesAreOneError) {
  std::string garbage(64 * 1024, '\0');
  for (std::size_t i = 0; i < garbage.size(); ++i) {
    garbage[i] = static_cast<char>((i * 2654435761u) >> 13);
  }
  garbage[100] = '\0';
  const DbcParseResult bin = parse_dbc(garbage, "g.dbc");
  ASSERT_EQ(bin.diagnostics.size(), 1u) << dump(bin);
  EXPECT_NE(
      bin.diagnostics[0].to_string().find(": error: binary data (a NUL byte): not a DBC file"),
      std::string::npos);
  for (const char* empty : {"", "  \n\r\n\t"}) {
    const DbcParseResult e = parse_dbc(empty, "e.dbc");
    EXPECT_EQ(lines(e), std::vector<std::string>{"e.dbc: error: empty file: not a DBC file"});
  }
  const DbcParseResult none = parse_dbc("VERSION \"1\"\n", "n.dbc");
  EXPECT_EQ(lines(none), std::vector<std::string>{"n.dbc: warning: no message (BO_) in the file"});
}

TEST(DbcManyHands, HugeTokensAreCutInMessages) {
  const std::string huge(5'000'000, 'X');
  const DbcParseResult name = parse_dbc("BO_ 1 " + huge + ": 8 E\n", "h.dbc");
  ASSERT_EQ(name.error_count(), 1);
  EXPECT_EQ(name.diagnostics[0].message,
            "message name longer than 256 characters, found 'XXXXXXXXXXXXXXXXXXXX'");
  const DbcParseResult junk = parse_dbc(
      "BO_ 1 A: 8 E\n SG_ S : 0|8@1+ (1,0) [0|0] \"\" " + std::string("\x01\x02") + huge + "\n",
      "j.dbc");
  for (const auto& d : junk.diagnostics) EXPECT_LT(d.to_string().size(), 200u) << d.to_string();
}

const char* kLoneM = R"(BO_ 1 Pages: 8 E
 SG_ Page m : 6|2@1+ (1,0) [0|0] "" E
 SG_ P2 m2 : 8|8@1+ (1,0) [0|0] "" E
 SG_ P3 m3 : 8|8@1+ (1,0) [0|0] "" E
)";

TEST(DbcManyHands, ALoneLowercaseMIsTheSwitch) {
  const DbcParseResult r = parse_dbc(kLoneM, "m.dbc");
  EXPECT_EQ(lines(r), std::vector<std::string>{"m.dbc:2: warning: signal Page: multiplexer switch "
                                               "written as a lone 'm'; read as 'M'"});
  const Message& m = r.database.messages.at(0);
  EXPECT_TRUE(m.signals[0].is_multiplexor);
  EXPECT_EQ(m.signals[1].mux_parent, 0);
  EXPECT_EQ(m.signals[2].mux_parent, 0);
  // Decoded as pages: with Page = 2 only P2 is present (no overlap of P2 and P3).
  std::optional<Decoder> d = Decoder::compile(r.database);
  ASSERT_TRUE(d);
  CanFrame f;
  f.id = 1;
  f.len = 8;
  f.data[0] = 2 << 6;
  f.data[1] = 42;
  std::vector<int> present;
  d->decode(f, [&](int i, double) { present.push_back(i); });
  EXPECT_EQ(present, (std::vector<int>{0, 1}));
  DbcParseOptions strict;
  strict.strict = true;
  EXPECT_EQ(parse_dbc(kLoneM, "m.dbc", strict).error_count(), 1);
}

TEST(DbcManyHands, MultiplexerValuesBeyondTheSwitch) {
  const DbcParseResult overflow = parse_dbc(
      "BO_ 1 A: 8 E\n SG_ S M : 0|8@1+ (1,0) [0|0] \"\" E\n"
      " SG_ P m99999999999999999999 : 8|8@1+ (1,0) [0|0] \"\" E\n",
      "o.dbc");
  EXPECT_EQ(lines(overflow),
            std::vector<std::string>{"o.dbc:3:8: error: multiplexer value above 64 bits, found "
                                     "'m9999999999999999999'"});
  const DbcParseResult wide = parse_dbc(
      "BO_ 1 A: 8 E\n SG_ S M : 0|2@1+ (1,0) [0|0] \"\" E\n"
      " SG_ P m4 : 8|8@1+ (1,0) [0|0] \"\" E\n",
      "w.dbc");
  EXPECT_EQ(lines(wide), std::vector<std::string>{
                             "w.dbc:3: warning: signal P of message A can never be present: its "
                             "multiplexer value 4 exceeds what switch S (2 bits) can hold"});
}

// Found by fuzz_dbc_parser (UBSan: 1e+53 converted to int64): a value description's raw value
// beyond what the int64 key holds is reported and left out; the others load.
TEST(DbcManyHands, ValueDescriptionsBeyondTheInt64RangeAreLeftOut) {
  const char* text = R"(BO_ 1 A: 8 E
 SG_ S : 0|64@1+ (1,0) [0|0] "" E
VAL_ 1 S 1e53 "huge" -9223372036854775808 "min" 18446744073709551615 "SNA" -1e19 "below" 2 "two" ;
)";
  const DbcParseResult r = parse_dbc(text, "v.dbc");
  EXPECT_EQ(lines(r),
            (std::vector<std::string>{
                "v.dbc:3: warning: VAL_ value 1e+53 is outside the 64-bit integer range; left out",
                "v.dbc:3: warning: VAL_ value 1.84467e+19 is outside the 64-bit integer range; "
                "left out",
                "v.dbc:3: warning: VAL_ value -1e+19 is outside the 64-bit integer range; left "
                "out"}))
      << dump(r);
  ASSERT_EQ(r.database.messages.size(), 1u);
  const std::vector<ValueDescription>& values = r.database.messages[0].signals[0].values;
  ASSERT_EQ(values.size(), 2u);
  EXPECT_EQ(values[0].value, INT64_MIN);
  EXPECT_EQ(values[0].text, "min");
  EXPECT_EQ(values[1].value, 2);
  EXPECT_EQ(values[1].text, "two");
  DbcParseOptions strict;
  strict.strict = true;
  EXPECT_EQ(parse_dbc(text, "v.dbc", strict).error_count(), 3);
}

TEST(DbcManyHands, ScalingRangesAndNamesThatCannotBeMeant) {
  const DbcParseResult r = parse_dbc(R"(BO_ 1 A: 8 E
 SG_ Zero : 0|8@1+ (0,5) [0|0] "" E
 SG_ Swapped : 8|8@1+ (1,0) [10|0] "" E
 SG_ Yaw : 16|16@1- (0.01,0) [0|655.35] "deg/s" E
BO_ 2 A: 8 E
)",
                                     "s.dbc");
  EXPECT_EQ(lines(r),
            (std::vector<std::string>{
                "s.dbc:2: warning: signal Zero: factor 0: its value is always the offset",
                "s.dbc:3: warning: signal Swapped: minimum above maximum; range ignored",
                "s.dbc:5: warning: message name A used twice (first at line 1)",
                "s.dbc:4: warning: signal Yaw of message A: declared range [0|655.35] lies outside "
                "what its 16 signed bits carry [-327.68|327.67]; vmass does not discard values by "
                "DBC ranges"}))
      << dump(r);
  EXPECT_FALSE(r.database.messages[0].signals[1].has_range);
  DbcParseOptions strict;
  strict.strict = true;
  // Deviations become errors in strict mode; the declared range stays a warning.
  EXPECT_EQ(parse_dbc(R"(BO_ 1 A: 8 E
 SG_ Yaw : 16|16@1- (0.01,0) [0|655.35] "deg/s" E
)",
                      "s.dbc", strict)
                .error_count(),
            0);
}

}  // namespace
}  // namespace vmass::can

// A DBC loads the same whatever its line endings: LF (Unix), CRLF (Windows) or CR alone (old
// Mac). Every real file of tests/data/dbc, converted to each, gives the same messages, signals
// (with their lines), comments and diagnostics (with their lines and columns).
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>

#include "vmass/can/dbc.hpp"

namespace vmass::can {
namespace {

std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

/// The text with every line ending (LF or CRLF) replaced by `eol`.
std::string with_line_endings(const std::string& text, const std::string& eol) {
  std::string out;
  out.reserve(text.size() + text.size() / 16);
  for (std::size_t i = 0; i < text.size(); ++i) {
    if (text[i] == '\r' && i + 1 < text.size() && text[i + 1] == '\n') continue;
    if (text[i] == '\n') {
      out += eol;
    } else {
      out += text[i];
    }
  }
  return out;
}

/// What a parse gives, line endings aside: names, lines, layouts, comments, diagnostics.
std::string summary(const DbcParseResult& r) {
  std::ostringstream s;
  for (const Message& m : r.database.messages) {
    s << "BO " << m.id << " " << m.name << " " << m.length << " @" << m.line << " '" << m.comment
      << "'\n";
    for (const Signal& g : m.signals) {
      s << "  SG " << g.name << " " << g.start_bit << "|" << g.length << " " << g.factor << " "
        << g.offset << " " << g.unit << " @" << g.line << " '" << g.comment << "' "
        << g.values.size() << "\n";
    }
  }
  for (const DbcDiagnostic& d : r.diagnostics) s << d.to_string() << "\n";
  return s.str();
}

class DbcLineEndings : public ::testing::TestWithParam<const char*> {};

TEST_P(DbcLineEndings, CrOnlyAndCrlfLoadLikeLf) {
  const std::string name = std::string(GetParam()) + ".dbc";
  const std::string text = read_file(std::string(VMASS_TEST_DATA_DIR) + "/dbc/" + name);
  ASSERT_FALSE(text.empty());
  const DbcParseResult lf = parse_dbc(with_line_endings(text, "\n"), name);
  const DbcParseResult cr = parse_dbc(with_line_endings(text, "\r"), name);
  const DbcParseResult crlf = parse_dbc(with_line_endings(text, "\r\n"), name);
  ASSERT_GT(lf.database.messages.size(), 0u);
  EXPECT_EQ(cr.database.messages.size(), lf.database.messages.size());
  EXPECT_EQ(summary(cr), summary(lf));
  EXPECT_EQ(summary(crlf), summary(lf));
}

INSTANTIATE_TEST_SUITE_P(RealFiles, DbcLineEndings,
                         ::testing::Values("toyota_prius_2010_pt", "vw_mqb", "hyundai_2015_mcan",
                                           "FORD_CADS_64", "tesla_model3_vehicle"));

TEST(DbcLineEndingsLocations, ErrorsInACrOnlyFileHaveTheirLineAndColumn) {
  const std::string text =
      "VERSION \"\"\r\rBO_ 100 Speed: 8 ECU\r SG_ VehicleSpeed : x|16@1+ (0.01,0) [0|655.35] "
      "\"km/h\" ECU\r\rBO_ 200 Other: 8 ECU\r SG_ A : 0|8@1+ (1,0) [0|255] \"\" ECU\r";
  const DbcParseResult r = parse_dbc(text, "old_mac.dbc");
  ASSERT_EQ(r.error_count(), 1) << summary(r);
  EXPECT_EQ(r.diagnostics[0].line, 4);
  EXPECT_EQ(r.diagnostics[0].column, 21);
  ASSERT_EQ(r.database.messages.size(), 2u);
  EXPECT_EQ(r.database.messages[1].line, 6);
  EXPECT_EQ(r.database.messages[1].signals.at(0).line, 7);
}

TEST(DbcLineEndingsLocations, ACommentSpanningCrOnlyLinesKeepsItsBreak) {
  const DbcParseResult r = parse_dbc(
      "VERSION \"\"\rBO_ 100 Speed: 8 ECU\r SG_ A : 0|8@1+ (1,0) [0|255] \"\" ECU\r"
      "CM_ BO_ 100 \"first\rsecond\";\r",
      "old_mac.dbc");
  ASSERT_EQ(r.database.messages.size(), 1u);
  EXPECT_EQ(r.database.messages[0].comment, "first\nsecond");
}

}  // namespace
}  // namespace vmass::can

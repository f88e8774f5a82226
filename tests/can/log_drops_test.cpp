// No text log reader drops a line without counting it: a line that carried a frame, with any
// one of its fields broken (garbage, a number out of range, the field missing), is read or
// corrupt (counted, reported with why), never taken for a comment or an event. The lines that
// are events stay events (they carry no frame).
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "vmass/can/asc_log.hpp"
#include "vmass/can/candump_screen.hpp"
#include "vmass/can/log_line_parser.hpp"
#include "vmass/can/trc_log.hpp"

namespace vmass::can {
namespace {

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> out;
  std::size_t p = 0;
  while (p < line.size()) {
    while (p < line.size() && line[p] == ' ') ++p;
    const std::size_t b = p;
    while (p < line.size() && line[p] != ' ') ++p;
    if (p > b) out.push_back(line.substr(b, p - b));
  }
  return out;
}

std::string join(const std::vector<std::string>& tokens) {
  std::string out;
  for (const std::string& t : tokens) out += (out.empty() ? "" : " ") + t;
  return out;
}

/// Every variant of `line` with one token replaced by garbage or a huge number, or removed.
std::vector<std::string> broken_variants(const std::string& line) {
  const std::vector<std::string> tokens = split(line);
  std::vector<std::string> out;
  for (std::size_t i = 0; i < tokens.size(); ++i) {
    for (const char* replacement : {"Z!", "99999", "4294967296", ""}) {
      std::vector<std::string> t = tokens;
      if (*replacement == '\0') {
        t.erase(t.begin() + static_cast<std::ptrdiff_t>(i));
      } else {
        t[i] = replacement;
      }
      out.push_back(join(t));
    }
  }
  return out;
}

/// A parser with its headers read, for each broken variant of `frame_line`.
template <typename MakeParser>
void expect_never_silent(MakeParser make, const std::vector<std::string>& headers,
                         const std::string& frame_line) {
  {
    auto p = make();
    std::string why;
    for (const std::string& h : headers) p->parse(h, nullptr, &why);
    CandumpRecord r;
    ASSERT_EQ(p->parse(frame_line, &r, &why), CandumpLine::kFrame) << frame_line << ": " << why;
  }
  for (const std::string& variant : broken_variants(frame_line)) {
    auto p = make();
    std::string why;
    for (const std::string& h : headers) p->parse(h, nullptr, &why);
    CandumpRecord r;
    why.clear();
    const CandumpLine kind = p->parse(variant, &r, &why);
    EXPECT_NE(kind, CandumpLine::kComment) << "dropped without a count: '" << variant << "'";
    if (kind == CandumpLine::kCorrupt) {
      EXPECT_FALSE(why.empty()) << variant;
    }
  }
}

TEST(LogDrops, AscChannelAbove255IsCorruptNotAnEvent) {
  AscParser p;
  std::string why;
  CandumpRecord r;
  EXPECT_EQ(p.parse("   0.015991 256  123  Rx   d 1 01", &r, &why), CandumpLine::kCorrupt);
  EXPECT_EQ(why, "channel above 255");
  EXPECT_EQ(p.parse("   0.015991 CANFD 300 Rx 123 1 0 1 1 01", &r, &why), CandumpLine::kCorrupt);
  EXPECT_EQ(p.parse("   0.015991", &r, &why), CandumpLine::kCorrupt);
  EXPECT_EQ(p.parse("   0.015991 1", &r, &why), CandumpLine::kCorrupt);
  ASSERT_EQ(p.parse("   0.015991 255  123  Rx   d 1 01", &r, &why), CandumpLine::kFrame) << why;
  EXPECT_EQ(r.interface, "can254");
}

TEST(LogDrops, AscEventsStayEvents) {
  AscParser p;
  std::string why;
  for (const char* event :
       {"   0.000000 Start of measurement", "   2.501000 1  Statistic: D 0 R 0 XD 0 XR 0",
        "   3.000000 CAN 1 Status:chip status error active", "   4.000000 1  SV: 1 0 1 ::x = 1",
        "   5.000000 1  J1939TP FEEBp 6 0 0 - Rx d 23 01 02"}) {
    EXPECT_EQ(p.parse(event, nullptr, &why), CandumpLine::kComment) << event;
  }
}

TEST(LogDrops, AscFrameLinesAreReadOrCounted) {
  auto make = [] { return std::make_unique<AscParser>(); };
  const std::vector<std::string> headers = {"date Wed Jan 10 10:55:25.123 am 2024",
                                            "base hex  timestamps absolute"};
  expect_never_silent(make, headers, "0.015991 1 123 Rx d 8 01 02 03 04 05 06 07 08");
  expect_never_silent(make, headers, "1.000000 2 1ABCDEF0x Tx r 4");
  expect_never_silent(make, headers,
                      "1.200000 CANFD 1 Rx 123 1 0 9 12 00 01 02 03 04 05 06 07 "
                      "08 09 0a 0b");
}

TEST(LogDrops, TrcUnknownMessageTypesAreCorrupt) {
  TrcParser v2;
  std::string why;
  CandumpRecord r;
  v2.parse(";$FILEVERSION=2.1", &r, &why);
  v2.parse(";$COLUMNS=N,O,T,B,I,d,R,L,D", &r, &why);
  EXPECT_EQ(v2.parse("  1  12.345 XX  1  0123 Rx -  1  01", &r, &why), CandumpLine::kCorrupt);
  EXPECT_NE(why.find("message type"), std::string::npos) << why;
  EXPECT_EQ(v2.parse("  2  12.345 ST  1  0000 Rx -  0", &r, &why), CandumpLine::kComment);
  EXPECT_EQ(v2.parse("  3  12.345 EV  1  0000 Rx -  0", &r, &why), CandumpLine::kComment);
  TrcParser v11;
  v11.parse(";$FILEVERSION=1.1", &r, &why);
  EXPECT_EQ(v11.parse("  1)  1841.5  Xx  0123  1  AA", &r, &why), CandumpLine::kCorrupt);
  EXPECT_EQ(v11.parse("  2)  1842.0  Warng  FFFFFFFF  4  00 00 00 08  BUSHEAVY", &r, &why),
            CandumpLine::kComment);
}

TEST(LogDrops, TrcFrameLinesAreReadOrCounted) {
  auto make = [] { return std::make_unique<TrcParser>(); };
  expect_never_silent(make, {";$FILEVERSION=2.1", ";$COLUMNS=N,O,T,B,I,d,R,L,D"},
                      "1 12.345 DT 1 0123 Rx - 3 01 02 03");
  expect_never_silent(make, {";$FILEVERSION=2.1", ";$COLUMNS=N,O,T,B,I,d,R,L,D"},
                      "2 13.000 FB 2 18FF0000 Tx - 9 00 01 02 03 04 05 06 07 08 09 0A 0B");
  expect_never_silent(make, {";$FILEVERSION=1.1"}, "2) 1841.5 Rx 18EFC0F9 2 AA BB");
  expect_never_silent(make, {";$FILEVERSION=1.3"}, "5) 1844.5 2 Tx 0123 - 2 0A 0B");
  expect_never_silent(make, {}, "1) 1841 0001 8 00 01 02 03 04 05 06 07");
}

TEST(LogDrops, CandumpFrameLinesAreReadOrCounted) {
  expect_never_silent([] { return make_log_line_parser(LogFormat::kCandump, true); }, {},
                      "(1594172461.968006) vcan0 123#DEADBEEF");
  expect_never_silent([] { return make_log_line_parser(LogFormat::kCandumpScreen, true); }, {},
                      "(1594172461.968006) vcan0 12345678 [2] AB CD");
}

}  // namespace
}  // namespace vmass::can

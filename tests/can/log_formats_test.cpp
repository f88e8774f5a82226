// The text CAN log parsers (ASC, TRC, candump screen output) and format detection, line by line
// against frames worked out by hand from the formats' documentation and real writers' lines
// (CANoe, PCAN-View, python-can, can-utils). The replay of whole files written by independent
// writers is tests/logs.
#include <gtest/gtest.h>

#include <string>

#include "vmass/can/asc_log.hpp"
#include "vmass/can/candump_screen.hpp"
#include "vmass/can/log_format.hpp"
#include "vmass/can/trc_log.hpp"

namespace vmass::can {
namespace {

CandumpLine parse(LogLineParser& p, const std::string& line, CanFrame* f, std::string* why) {
  CandumpRecord r;
  const CandumpLine kind = p.parse(line, &r, why);
  if (kind == CandumpLine::kFrame) *f = r.frame;
  return kind;
}

constexpr std::int64_t kJan10_2024_105525_us = 1704884125LL * 1000000;  // date -u -d ... +%s

TEST(AscDate, CanoeAndPythonCanSpellings) {
  std::int64_t t = 0;
  ASSERT_TRUE(parse_asc_date("Wed Jan 10 10:55:25.123 am 2024", &t));
  EXPECT_EQ(t, kJan10_2024_105525_us + 123000);
  ASSERT_TRUE(parse_asc_date("Wed Jan 10 10:55:25.123 pm 2024", &t));
  EXPECT_EQ(t, kJan10_2024_105525_us + 12LL * 3600 * 1000000 + 123000);
  ASSERT_TRUE(parse_asc_date("Thu Jan 01 00:00:00.5 1970", &t));  // python-can: unpadded ms
  EXPECT_EQ(t, 5000);
  EXPECT_FALSE(parse_asc_date("Mi Jan 10 10:55:25 2024 extra words", &t));
  EXPECT_FALSE(parse_asc_date("Wed Foo 10 10:55:25.123 2024", &t));
}

TEST(AscParser, ClassicExtendedRemoteErrorAndFdFrames) {
  AscParser p;
  CanFrame f;
  std::string why;
  EXPECT_EQ(parse(p, "date Wed Jan 10 10:55:25.123 am 2024", &f, &why), CandumpLine::kComment);
  EXPECT_EQ(parse(p, "base hex  timestamps absolute", &f, &why), CandumpLine::kComment);
  EXPECT_EQ(parse(p, "Begin Triggerblock Wed Jan 10 10:55:25.123 am 2024", &f, &why),
            CandumpLine::kComment);
  EXPECT_EQ(parse(p, "   0.000000 Start of measurement", &f, &why), CandumpLine::kComment);
  ASSERT_EQ(parse(p,
                  "   0.015991 1  123             Rx   d 8 01 02 03 04 05 06 07 08  Length = "
                  "231000 BitCount = 119 ID = 291",
                  &f, &why),
            CandumpLine::kFrame)
      << why;
  EXPECT_EQ(f.time_us, kJan10_2024_105525_us + 123000 + 15991);
  EXPECT_EQ(f.id, 0x123u);
  EXPECT_EQ(f.flags, 0);
  ASSERT_EQ(f.len, 8);
  EXPECT_EQ(f.data[7], 0x08);
  ASSERT_EQ(parse(p, "   1.000000 2  1ABCDEF0x       Tx   r 4", &f, &why), CandumpLine::kFrame);
  EXPECT_EQ(f.id, 0x1ABCDEF0u);
  EXPECT_EQ(f.flags, kExtended | kRemote);
  EXPECT_EQ(f.len, 4);
  ASSERT_EQ(parse(p, "   1.100000 1  ErrorFrame", &f, &why), CandumpLine::kFrame);
  EXPECT_TRUE(f.error());
  ASSERT_EQ(parse(p,
                  "   1.200000 CANFD   1 Rx        123  Name  1 0 9 12 00 01 02 03 04 05 06 "
                  "07 08 09 0a 0b   0    0     1000        0        0        0        0",
                  &f, &why),
            CandumpLine::kFrame)
      << why;
  EXPECT_EQ(f.flags, kFd | kFdBrs);
  ASSERT_EQ(f.len, 12);
  EXPECT_EQ(f.data[11], 0x0B);
  EXPECT_EQ(parse(p, "   2.501000 1  Statistic: D 0 R 0 XD 0 XR 0 E 0 O 0 B 0.00%", &f, &why),
            CandumpLine::kComment);
  EXPECT_EQ(parse(p, "End TriggerBlock", &f, &why), CandumpLine::kComment);
}

TEST(AscParser, CorruptLinesSayWhy) {
  AscParser p;
  CanFrame f;
  std::string why;
  EXPECT_EQ(parse(p, "   0.1 1  123  Rx   d 8 01 02", &f, &why), CandumpLine::kCorrupt);
  EXPECT_NE(why.find("fewer data bytes"), std::string::npos) << why;
  EXPECT_EQ(parse(p, "   0.1 1  8FF  Rx   d 1 01", &f, &why), CandumpLine::kCorrupt);
  EXPECT_EQ(parse(p, "   0.1 1  123  Rx   x 1 01", &f, &why), CandumpLine::kCorrupt);
  EXPECT_EQ(parse(p, "   0.1 1  123  Rx   d 1 GG", &f, &why), CandumpLine::kCorrupt);
  EXPECT_EQ(parse(p, "this is not an ASC line", &f, &why), CandumpLine::kCorrupt);
}

TEST(AscParser, DecimalBaseAndRelativeTimes) {
  AscParser p;
  CanFrame f;
  std::string why;
  EXPECT_EQ(parse(p, "base dec  timestamps relative", &f, &why), CandumpLine::kComment);
  ASSERT_EQ(parse(p, "0.5 1  291 Rx d 2 255 16", &f, &why), CandumpLine::kFrame) << why;
  EXPECT_EQ(f.id, 291u);
  EXPECT_EQ(f.data[0], 255);
  EXPECT_EQ(f.time_us, 500000);
  ASSERT_EQ(parse(p, "0.25 1  291 Rx d 0", &f, &why), CandumpLine::kFrame);
  EXPECT_EQ(f.time_us, 750000);  // relative: from the previous line
}

TEST(TrcParser, Version21AsPythonCanAndPcanViewWriteIt) {
  TrcParser p;
  CanFrame f;
  std::string why;
  EXPECT_EQ(parse(p, ";$FILEVERSION=2.1", &f, &why), CandumpLine::kComment);
  EXPECT_EQ(parse(p, ";$STARTTIME=45301.4550115741", &f, &why), CandumpLine::kComment);
  EXPECT_EQ(parse(p, ";$COLUMNS=N,O,T,B,I,d,R,L,D", &f, &why), CandumpLine::kComment);
  ASSERT_EQ(parse(p, "      1       12.345 DT  1     0123 Rx -  3    01 02 03", &f, &why),
            CandumpLine::kFrame)
      << why;
  // 45301.4550115741 days after 1899-12-30 = 2024-01-10 10:55:12.999 UTC (+ offset 12.345 ms)
  EXPECT_NEAR(static_cast<double>(f.time_us), 1704884113000000.0 + 12345.0, 10.0);
  EXPECT_EQ(f.id, 0x123u);
  EXPECT_EQ(f.len, 3);
  ASSERT_EQ(parse(p,
                  "      2       13.000 FB  2 18FF0000 Tx -  9    00 01 02 03 04 05 06 07 08 "
                  "09 0A 0B",
                  &f, &why),
            CandumpLine::kFrame)
      << why;
  EXPECT_EQ(f.flags, kExtended | kFd | kFdBrs);
  EXPECT_EQ(f.len, 12);
  ASSERT_EQ(parse(p, "      3       14.000 RR  1     0456 Rx -  2", &f, &why), CandumpLine::kFrame);
  EXPECT_TRUE(f.remote());
  EXPECT_EQ(parse(p, "      4       15.000 ST  1     0000 Rx -  0", &f, &why),
            CandumpLine::kComment);
  EXPECT_EQ(parse(p, "      5       16.000 DT  1     0123 Rx -  8    01 02", &f, &why),
            CandumpLine::kCorrupt);
}

TEST(TrcParser, Versions10To13) {
  TrcParser v10;
  CanFrame f;
  std::string why;
  ASSERT_EQ(parse(v10, "     1)      1841 0001 8 00 01 02 03 04 05 06 07", &f, &why),
            CandumpLine::kFrame)
      << why;
  EXPECT_EQ(f.time_us, 1841000);
  EXPECT_EQ(f.len, 8);
  TrcParser v11;
  EXPECT_EQ(parse(v11, ";$FILEVERSION=1.1", &f, &why), CandumpLine::kComment);
  ASSERT_EQ(parse(v11, "     2)      1841.5  Rx     18EFC0F9  2  AA BB", &f, &why),
            CandumpLine::kFrame)
      << why;
  EXPECT_EQ(f.time_us, 1841500);
  EXPECT_EQ(f.flags, kExtended);
  EXPECT_EQ(f.data[1], 0xBB);
  EXPECT_EQ(parse(v11, "     3)      1842.0  Warng  FFFFFFFF  4  00 00 00 08  BUSHEAVY", &f, &why),
            CandumpLine::kComment);
  EXPECT_EQ(parse(v11, "     4)      1843.0  Rx     0001  8  RTR", &f, &why), CandumpLine::kFrame);
  EXPECT_TRUE(f.remote());
  TrcParser v13;
  EXPECT_EQ(parse(v13, ";$FILEVERSION=1.3", &f, &why), CandumpLine::kComment);
  CandumpRecord r;
  ASSERT_EQ(v13.parse("     5)      1844.5 2  Tx         0123 -  2  0A 0B", &r, &why),
            CandumpLine::kFrame)
      << why;
  EXPECT_EQ(r.frame.time_us, 1844500);
  EXPECT_EQ(r.frame.id, 0x123u);
  EXPECT_EQ(r.frame.data[1], 0x0B);
  EXPECT_EQ(r.interface, "can1");  // bus 2
}

TEST(CandumpScreenParser, WithAndWithoutTimes) {
  CandumpScreenParser decode(false);
  CanFrame f;
  std::string why;
  ASSERT_EQ(parse(decode, "  can0  1F0   [8]  80 4A 0F 00 00 00 00 00", &f, &why),
            CandumpLine::kFrame)
      << why;
  EXPECT_EQ(f.id, 0x1F0u);
  EXPECT_EQ(f.data[1], 0x4A);
  EXPECT_EQ(f.time_us, 0);
  ASSERT_EQ(parse(decode, "(1594172461.968006)  vcan0  12345678   [2]  AB CD   '..'", &f, &why),
            CandumpLine::kFrame);
  EXPECT_EQ(f.time_us, 1594172461968006);
  EXPECT_EQ(f.flags, kExtended);
  ASSERT_EQ(parse(decode, "  can0  123   [2]  remote request", &f, &why), CandumpLine::kFrame);
  EXPECT_TRUE(f.remote());
  ASSERT_EQ(parse(decode, "  can0  123  [12]  00 01 02 03 04 05 06 07 08 09 0A 0B", &f, &why),
            CandumpLine::kFrame);
  EXPECT_TRUE(f.fd());
  EXPECT_EQ(parse(decode, "  can0  123   [3]  01 02", &f, &why), CandumpLine::kCorrupt);
  CandumpScreenParser recording(true);
  EXPECT_EQ(parse(recording, "  can0  1F0   [1]  80", &f, &why), CandumpLine::kCorrupt);
  EXPECT_NE(why.find("no time"), std::string::npos);
}

TEST(DetectLogFormat, FromContentAlone) {
  EXPECT_EQ(detect_log_format("(1700000000.000000) can0 123#00\n"), LogFormat::kCandump);
  EXPECT_EQ(detect_log_format("# comment\n\n(1.000000) can0 123#00\n"), LogFormat::kCandump);
  EXPECT_EQ(detect_log_format("  can0  123   [1]  00\n"), LogFormat::kCandumpScreen);
  EXPECT_EQ(detect_log_format("date Wed Jan 10 10:55:25.123 am 2024\nbase hex\n"), LogFormat::kAsc);
  EXPECT_EQ(detect_log_format(";$FILEVERSION=2.1\n"), LogFormat::kTrc);
  EXPECT_EQ(detect_log_format(";####\n;   Start time: 1/1/2024\n     1)      1841 0001 1 00\n"),
            LogFormat::kTrc);
  EXPECT_EQ(detect_log_format(std::string("LOGG\x90\0\0\0", 8)), LogFormat::kBlf);
  EXPECT_EQ(detect_log_format("MDF     4.11    amdf"), LogFormat::kMdf4);
  EXPECT_EQ(detect_log_format("MDF     3.30    "), LogFormat::kMdf3);
  EXPECT_EQ(detect_log_format("\xED\xA1\xDA\x01\0\0\0\0"), LogFormat::kLcmLog);
  EXPECT_EQ(detect_log_format("time_s,mass_kg\n0.0,1500\n"), LogFormat::kUnknown);
  EXPECT_EQ(detect_log_format(std::string("\x89PNG\r\n\x1a\n\0\0", 10)), LogFormat::kUnknown);
}

}  // namespace
}  // namespace vmass::can

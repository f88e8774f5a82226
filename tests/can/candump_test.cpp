// candump -l log reader and writer.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <random>
#include <sstream>
#include <string>

#include "vmass/can/candump.hpp"

namespace vmass::can {
namespace {

// The record's interface views the line: keep the last line alive until the next call.
CandumpRecord parse_ok(const std::string& line) {
  static std::string kept;
  kept = line;
  CandumpRecord r;
  std::string err;
  EXPECT_EQ(parse_candump_line(kept, &r, &err), CandumpLine::kFrame) << line << ": " << err;
  return r;
}

std::string parse_error(const std::string& line) {
  CandumpRecord r;
  std::string err;
  EXPECT_EQ(parse_candump_line(line, &r, &err), CandumpLine::kCorrupt) << line;
  return err;
}

TEST(Candump, ParsesEveryFrameForm) {
  CandumpRecord r = parse_ok("(1700000000.123456) can0 123#DEADBEEF");
  EXPECT_EQ(r.frame.time_us, 1700000000123456);
  EXPECT_EQ(r.interface, "can0");
  EXPECT_EQ(r.frame.id, 0x123u);
  EXPECT_EQ(r.frame.flags, 0);
  ASSERT_EQ(r.frame.len, 4);
  EXPECT_EQ(r.frame.data[0], 0xDE);
  EXPECT_EQ(r.frame.data[3], 0xEF);
  EXPECT_EQ(r.direction, '\0');

  r = parse_ok("(1700000000.123456789) vcan0 1ABCDEF0#0102 T");
  EXPECT_EQ(r.frame.time_us, 1700000000123456);  // nanoseconds truncated
  EXPECT_TRUE(r.frame.extended());
  EXPECT_EQ(r.frame.id, 0x1ABCDEF0u);
  EXPECT_EQ(r.frame.len, 2);
  EXPECT_EQ(r.direction, 'T');

  r = parse_ok("(0000000001.000001) can1 00000123#");  // 8 digits: extended even if small
  EXPECT_TRUE(r.frame.extended());
  EXPECT_EQ(r.frame.len, 0);
  EXPECT_EQ(r.frame.time_us, 1000001);

  r = parse_ok("(1.500000) can0 7FF##3" + std::string(128, 'A') + " R");
  EXPECT_TRUE(r.frame.fd());
  EXPECT_TRUE(r.frame.flags & kFdBrs);
  EXPECT_TRUE(r.frame.flags & kFdEsi);
  EXPECT_EQ(r.frame.len, 64);
  EXPECT_EQ(r.frame.data[63], 0xAA);
  EXPECT_EQ(r.direction, 'R');

  r = parse_ok("(1.500000) can0 100##5");  // BRS and FDF, as newer kernels report FD frames
  EXPECT_EQ(r.frame.flags, kFd | kFdBrs | kFdFdf);
  EXPECT_EQ(format_candump_line(r.frame, "can0"), "(0000000001.500000) can0 100##5\n");
  r = parse_ok("(1.500000) can0 100##0");
  EXPECT_TRUE(r.frame.fd());
  EXPECT_EQ(r.frame.len, 0);

  r = parse_ok("(1.500000) can0 123#R");
  EXPECT_TRUE(r.frame.remote());
  EXPECT_EQ(r.frame.len, 0);
  r = parse_ok("(1.500000) can0 12345678#R5");
  EXPECT_TRUE(r.frame.remote());
  EXPECT_TRUE(r.frame.extended());
  EXPECT_EQ(r.frame.len, 5);

  r = parse_ok("(1.500000) can0 20000004#0004000000000000");
  EXPECT_TRUE(r.frame.error());
  EXPECT_FALSE(r.frame.extended());
  EXPECT_EQ(r.frame.id, 4u);  // CAN_ERR_CRTL
  EXPECT_EQ(r.frame.data[1], 4);

  r = parse_ok("(1.500000) can0 123#11.22.33");  // cansend's separators
  EXPECT_EQ(r.frame.len, 3);
  EXPECT_EQ(r.frame.data[2], 0x33);
  r = parse_ok("(1.500000) can0 123#1122334455667788_C");  // len8_dlc
  EXPECT_EQ(r.frame.len, 8);
  r = parse_ok("(1.500000) can0 123#deadbeef\r");  // lower case, CRLF
  EXPECT_EQ(r.frame.data[0], 0xDE);
}

TEST(Candump, CommentsAndBlankLines) {
  CandumpRecord r;
  EXPECT_EQ(parse_candump_line("", &r), CandumpLine::kComment);
  EXPECT_EQ(parse_candump_line("   ", &r), CandumpLine::kComment);
  EXPECT_EQ(parse_candump_line("# recorded on the test track", &r), CandumpLine::kComment);
}

TEST(Candump, CorruptLinesSayWhy) {
  EXPECT_NE(parse_error("1700000000.123456 can0 123#00").find("'('"), std::string::npos);
  EXPECT_NE(parse_error("(1700000000.1234) can0 123#00").find("6 or 9"), std::string::npos);
  EXPECT_NE(parse_error("(1.000000) can0 1234#00").find("3 or 8"), std::string::npos);
  EXPECT_NE(parse_error("(1.000000) can0 800#00").find("7FF"), std::string::npos);
  EXPECT_NE(parse_error("(1.000000) can0 123#0").find("odd"), std::string::npos);
  EXPECT_NE(parse_error("(1.000000) can0 123#001122334455667788").find("more than 8"),
            std::string::npos);
  EXPECT_NE(parse_error("(1.000000) can0 123##1001122334455667788").find("CAN FD length"),
            std::string::npos);
  EXPECT_NE(parse_error("(1.000000) can0 123#XY").find("hexadecimal"), std::string::npos);
  EXPECT_NE(parse_error("(1.000000) can0 123#00 junk").find("after the frame"), std::string::npos);
  EXPECT_NE(parse_error("(1.000000) can0").find("frame"), std::string::npos);
  EXPECT_NE(parse_error("(1.000000) can0 FFFFFFFF#00").find("extra flag"), std::string::npos);
  EXPECT_NE(parse_error("(1.000000) can0 123#R9").find("remote"), std::string::npos);
}

TEST(Candump, TimestampsAreExactToTheMicrosecond) {
  // Integer arithmetic: no rounding, whatever the magnitude (12 digits of seconds at most).
  EXPECT_EQ(parse_ok("(999999999999.999999) can0 123#").frame.time_us, 999999999999999999);
  EXPECT_EQ(parse_ok("(999999999999.999999999) can0 123#").frame.time_us, 999999999999999999);
  EXPECT_EQ(parse_ok("(000000000000.000001) can0 123#").frame.time_us, 1);
  EXPECT_EQ(parse_ok("(0.000000999) can0 123#").frame.time_us, 0);  // nanoseconds truncated
  EXPECT_EQ(parse_ok("(1700000000.100000) can0 123#").frame.time_us, 1700000000100000);
  EXPECT_EQ(parse_error("(1234567890123.000000) can0 123#"),
            "more than 12 digits of seconds in the timestamp");
  EXPECT_EQ(parse_error("(-50.000000) can0 123#"),
            "negative time (before 1970): candump -l times are seconds since 1970");
  EXPECT_EQ(parse_error("(.000000) can0 123#"), "expected seconds in the timestamp");
  EXPECT_EQ(parse_error("(1.0000000000) can0 123#"), "timestamp needs 6 or 9 fractional digits");
  EXPECT_EQ(parse_error("(1.0000000) can0 123#"), "timestamp needs 6 or 9 fractional digits");
  EXPECT_EQ(parse_error("(1,000000) can0 123#"), "expected '.' in the timestamp");
  EXPECT_EQ(parse_error("(1.000000 can0 123#"), "expected ')' after the timestamp");
}

TEST(Candump, HexDigitsAreExactlyTheSixteenOfEitherCase) {
  EXPECT_EQ(parse_ok("(1.000000) can0 1aF#0a9FfA").frame.id, 0x1AFu);
  EXPECT_EQ(parse_ok("(1.000000) can0 1aF#0a9FfA").frame.data[2], 0xFA);
  // The bytes beside the digit ranges, and bytes above 0x7F (a signed char), are not digits.
  for (const char* bad : {"/", ":", "@", "G", "`", "g", "\xB0", "\xFF"}) {
    EXPECT_EQ(parse_error(std::string("(1.000000) can0 12") + bad + "#00"),
              "CAN id is not hexadecimal")
        << bad;
    EXPECT_EQ(parse_error(std::string("(1.000000) can0 123#0") + bad), "data is not hexadecimal")
        << bad;
  }
}

TEST(Candump, ReaderSkipsCountsAndReportsCorruptLines) {
  std::istringstream in(
      "(1.000000) can0 100#01\n"
      "# comment\n"
      "garbage line\n"
      "(1.000001) can0 101#0203\n"
      "(1.000002) can0 102#0\n"
      "\n"
      "(1.000003) can0 103##100\n"
      "(1.000004) can0 20000040#0000000000000000\n"
      "(1.000005) can0 104#R\n");
  CandumpReader reader(in, "drive.log");
  std::vector<std::string> reported;
  reader.on_error([&](const CandumpError& e) { reported.push_back(e.message); });
  CandumpRecord r;
  std::vector<std::uint32_t> ids;
  while (reader.next(&r)) ids.push_back(r.frame.id);
  EXPECT_EQ(ids, (std::vector<std::uint32_t>{0x100, 0x101, 0x103, 0x40, 0x104}));
  const CandumpStats& s = reader.stats();
  EXPECT_EQ(s.lines, 9u);
  EXPECT_EQ(s.frames, 5u);
  EXPECT_EQ(s.comments, 2u);
  EXPECT_EQ(s.corrupt, 2u);
  EXPECT_EQ(s.fd_frames, 1u);
  EXPECT_EQ(s.error_frames, 1u);
  EXPECT_EQ(s.remote_frames, 1u);
  ASSERT_EQ(reader.errors().size(), 2u);
  EXPECT_EQ(reader.errors()[0].line, 3);
  EXPECT_EQ(reader.errors()[1].line, 5);
  ASSERT_EQ(reported.size(), 2u);
  EXPECT_EQ(reported[0].rfind("drive.log:3: ", 0), 0u) << reported[0];
  EXPECT_EQ(reported[1].rfind("drive.log:5: ", 0), 0u) << reported[1];
}

TEST(Candump, WriterMatchesCandumpExactly) {
  CanFrame f;
  f.time_us = 1700000000123456;
  f.id = 0x123;
  f.len = 4;
  f.data[0] = 0xDE;
  f.data[1] = 0xAD;
  f.data[2] = 0xBE;
  f.data[3] = 0xEF;
  EXPECT_EQ(format_candump_line(f, "can0"), "(1700000000.123456) can0 123#DEADBEEF\n");
  f.time_us = 5;
  f.id = 0x1;
  f.flags = kExtended;
  f.len = 0;
  EXPECT_EQ(format_candump_line(f, "vcan0"), "(0000000000.000005) vcan0 00000001#\n");
  f.flags = kFd | kFdBrs;
  f.id = 0x7FF;
  f.len = 12;
  for (int i = 0; i < 12; ++i) f.data[i] = static_cast<std::uint8_t>(i);
  EXPECT_EQ(format_candump_line(f, "can0"),
            "(0000000000.000005) can0 7FF##1000102030405060708090A0B\n");
  f.flags = kRemote;
  f.len = 3;
  EXPECT_EQ(format_candump_line(f, "can0"), "(0000000000.000005) can0 7FF#R3\n");
  f.len = 0;
  EXPECT_EQ(format_candump_line(f, "can0"), "(0000000000.000005) can0 7FF#R\n");
  f.flags = kError;
  f.id = 0x40;
  f.len = 8;
  for (int i = 0; i < 8; ++i) f.data[i] = 0;
  EXPECT_EQ(format_candump_line(f, "can0"), "(0000000000.000005) can0 20000040#0000000000000000\n");
}

TEST(Candump, RandomFramesRoundTrip) {
  std::mt19937_64 rng(31);
  std::ostringstream out;
  CandumpWriter writer(out);
  std::vector<CanFrame> frames;
  const int lens[] = {0, 1, 8, 12, 16, 20, 24, 32, 48, 64};
  for (int i = 0; i < 2000; ++i) {
    CanFrame f;
    f.time_us = static_cast<std::int64_t>(rng() % 4000000000000000ull);
    const int kind = static_cast<int>(rng() % 5);
    f.flags = static_cast<std::uint8_t>(kind == 1 ? kExtended : 0);
    f.id = static_cast<std::uint32_t>(rng()) & (kind == 1 ? kEffMask : kSffMask);
    if (kind == 2) {
      f.flags = static_cast<std::uint8_t>(kFd | (rng() % 2 ? kFdBrs : 0) |
                                          (rng() % 2 ? kFdFdf : 0) | (rng() % 2 ? kExtended : 0));
      if (f.extended()) f.id = static_cast<std::uint32_t>(rng()) & kEffMask;
      f.len = static_cast<std::uint8_t>(lens[rng() % 10]);
    } else if (kind == 3) {
      f.flags = kRemote;
      f.len = static_cast<std::uint8_t>(rng() % 9);
    } else if (kind == 4) {
      f.flags = kError;
      f.id = static_cast<std::uint32_t>(rng()) & 0x1FF;
      f.len = 8;
    } else {
      f.len = static_cast<std::uint8_t>(rng() % 9);
    }
    if (!f.remote()) {
      for (int b = 0; b < f.len; ++b) f.data[b] = static_cast<std::uint8_t>(rng());
    }
    frames.push_back(f);
    writer.write(f, "can0");
  }
  std::istringstream in(out.str());
  CandumpReader reader(in);
  CandumpRecord r;
  std::size_t n = 0;
  while (reader.next(&r)) {
    ASSERT_LT(n, frames.size());
    const CanFrame& f = frames[n++];
    EXPECT_EQ(r.frame.time_us, f.time_us);
    EXPECT_EQ(r.frame.id, f.id);
    EXPECT_EQ(r.frame.flags, f.flags);
    EXPECT_EQ(r.frame.len, f.len);
    EXPECT_EQ(std::string(reinterpret_cast<const char*>(r.frame.data), r.frame.len),
              std::string(reinterpret_cast<const char*>(f.data), f.len));
  }
  EXPECT_EQ(n, frames.size());
  EXPECT_EQ(reader.stats().corrupt, 0u);
}

// can-utils' own log2asc parses what we write (an independent reader of the format).
TEST(Candump, CanUtilsLog2ascReadsOurFiles) {
  if (std::system("command -v log2asc >/dev/null 2>&1") != 0) {
    GTEST_SKIP() << "log2asc (can-utils) not installed";
  }
  const std::string dir = ::testing::TempDir();
  const std::string log = dir + "/vmass_candump_test.log";
  const std::string asc = dir + "/vmass_candump_test.asc";
  {
    std::ofstream out(log);
    CandumpWriter w(out);
    CanFrame f;
    f.time_us = 1700000000000000;
    f.id = 0x123;
    f.len = 2;
    f.data[0] = 0xAB;
    f.data[1] = 0xCD;
    w.write(f, "can0");
    f.time_us += 1500;
    f.flags = kExtended;
    f.id = 0x18DAF110;
    w.write(f, "can0");
    f.time_us += 1500;
    f.flags = kFd | kFdBrs;
    f.id = 0x456;
    f.len = 12;
    w.write(f, "can0");
  }
  ASSERT_EQ(std::system(("log2asc -I " + log + " -O " + asc + " can0").c_str()), 0);
  std::ifstream in(asc);
  std::stringstream ss;
  ss << in.rdbuf();
  const std::string text = ss.str();
  EXPECT_NE(text.find("123             Rx   d 2 AB CD"), std::string::npos) << text;
  EXPECT_NE(text.find("18DAF110x       Rx   d 2 AB CD"), std::string::npos) << text;
  EXPECT_NE(text.find("CANFD"), std::string::npos) << text;
  EXPECT_NE(text.find("0.003000"), std::string::npos) << text;
}

}  // namespace
}  // namespace vmass::can

// Files from many hands, read bounded: a directory, a FIFO without a writer, /dev/zero, an
// oversized file and a read error each give a message naming the path and why (and a FIFO does
// not block); lines are cut at their bound; excerpts quote at most 64 bytes, control bytes
// escaped.
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <fstream>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include <gtest/gtest.h>

#include "vmass/io/excerpt.hpp"
#include "vmass/io/line_reader.hpp"
#include "vmass/io/regular_file.hpp"

namespace vmass::io {
namespace {

class IoTest : public ::testing::Test {
 protected:
  void SetUp() override {
    char name[] = "/tmp/vmass_io_XXXXXX";
    ASSERT_NE(mkdtemp(name), nullptr);
    dir_ = name;
  }
  void TearDown() override { std::system(("rm -rf '" + dir_ + "'").c_str()); }
  std::string write(const std::string& name, const std::string& text) {
    const std::string path = dir_ + "/" + name;
    std::ofstream(path, std::ios::binary) << text;
    return path;
  }
  std::string dir_;
};

TEST_F(IoTest, ARegularFileIsReadWhole) {
  const std::string path = write("a.txt", "line 1\nline 2\n");
  const FileText f = read_regular_file(path, 100, "config");
  ASSERT_TRUE(f.ok()) << f.error;
  EXPECT_EQ(f.text, "line 1\nline 2\n");
}

TEST_F(IoTest, WhatIsNotARegularFileIsRefusedWithoutBlocking) {
  const std::string fifo = dir_ + "/fifo";
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  // No writer: an open without O_NONBLOCK would wait here for ever.
  EXPECT_EQ(read_regular_file(fifo, 100, "state file").error,
            fifo + ": cannot read the state file: is a FIFO (named pipe)");
  EXPECT_EQ(read_regular_file(dir_, 100, "DBC").error,
            dir_ + ": cannot read the DBC: is a directory");
  EXPECT_EQ(read_regular_file("/dev/zero", 100, "config").error,
            "/dev/zero: cannot read the config: is a character device");
  const FileText missing = read_regular_file(dir_ + "/none", 100, "config");
  EXPECT_TRUE(missing.missing);
  EXPECT_EQ(missing.error, dir_ + "/none: cannot open the config: No such file or directory");
}

TEST_F(IoTest, AFileAboveTheBoundIsRefused) {
  const std::string path = write("big", std::string(3u << 20, 'x'));
  EXPECT_EQ(read_regular_file(path, 2u << 20, "DBC").error,
            path + ": cannot read the DBC: larger than 2 MiB");
}

TEST_F(IoTest, StreamsMayBeFifosButNeverDevicesOrDirectories) {
  const std::string fifo = dir_ + "/fifo";
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  EXPECT_EQ(check_input_file(fifo, true), "");
  EXPECT_EQ(check_input_file(fifo, false), "is a FIFO (named pipe)");
  EXPECT_EQ(check_input_file("/dev/zero", true), "is a character device");
  EXPECT_EQ(check_input_file(dir_, true), "is a directory");
  EXPECT_EQ(check_input_file(write("log", "x"), false), "");
}

TEST(LineReader, LinesAreCutAtTheBoundAndTheRestSkipped) {
  std::istringstream in("short\r\n" + std::string(100, 'a') + "\nlast");
  LineReader lines(in, 10);
  std::string line;
  ASSERT_TRUE(lines.next(&line));
  EXPECT_EQ(line, "short");
  EXPECT_FALSE(lines.overlong());
  ASSERT_TRUE(lines.next(&line));
  EXPECT_EQ(line, std::string(10, 'a'));
  EXPECT_TRUE(lines.overlong());
  ASSERT_TRUE(lines.next(&line));  // the rest of the long line is skipped, not a line
  EXPECT_EQ(line, "last");
  EXPECT_EQ(lines.line_number(), 3);
  EXPECT_FALSE(lines.next(&line));
  EXPECT_EQ(lines.error(), "");
}

TEST(LineReader, AReadErrorIsNotTheEndOfTheFile) {
  // Reading a directory through a file stream fails with EISDIR on the first read.
  std::ifstream in("/tmp", std::ios::binary);
  ASSERT_TRUE(in.is_open());
  LineReader lines(in);
  std::string line;
  EXPECT_FALSE(lines.next(&line));
  EXPECT_EQ(lines.error(), "Is a directory");
}

TEST(LineReader, ALineOfTheBoundIsWholeAndTheLastLineNeedsNoNewline) {
  std::istringstream in(std::string(10, 'b') + "\n" + std::string(10, 'd') + "\r\n" +
                        std::string(11, 'c'));
  LineReader lines(in, 10);
  std::string_view line;
  ASSERT_TRUE(lines.next(&line));
  EXPECT_EQ(line, std::string(10, 'b'));
  EXPECT_FALSE(lines.overlong());
  ASSERT_TRUE(lines.next(&line));  // the '\r' is the line's 11th byte: the bound counts it
  EXPECT_EQ(line, std::string(10, 'd'));
  EXPECT_TRUE(lines.overlong());
  ASSERT_TRUE(lines.next(&line));  // cut, although the input ends without a newline
  EXPECT_EQ(line, std::string(10, 'c'));
  EXPECT_TRUE(lines.overlong());
  EXPECT_FALSE(lines.next(&line));
  EXPECT_EQ(lines.line_number(), 3);
}

/// A stream that hands out its text a few bytes per read, as a pipe does.
class TrickleBuf : public std::streambuf {
 public:
  TrickleBuf(std::string text, std::size_t chunk) : text_(std::move(text)), chunk_(chunk) {}

 protected:
  int_type underflow() override {
    if (at_ >= text_.size()) return traits_type::eof();
    const std::size_t n = std::min(chunk_, text_.size() - at_);
    char* begin = text_.data() + at_;
    setg(begin, begin, begin + n);
    at_ += n;
    return traits_type::to_int_type(*begin);
  }

 private:
  std::string text_;
  std::size_t chunk_;
  std::size_t at_ = 0;
};

TEST(LineReader, LinesSplitAcrossTheStreamsReadsComeWhole) {
  // Every line crosses a read (of 1 to 7 bytes), the long one many; '\r' and '\n' too.
  const std::string text = "one\r\ntwo\n\nthree\n" + std::string(25, 'x') + "\r\nfour";
  for (std::size_t chunk = 1; chunk <= 7; ++chunk) {
    TrickleBuf buf(text, chunk);
    std::istream in(&buf);
    LineReader lines(in, 20);
    std::vector<std::string> got;
    std::vector<bool> cut;
    std::string_view line;
    while (lines.next(&line)) {
      got.emplace_back(line);
      cut.push_back(lines.overlong());
    }
    EXPECT_EQ(got,
              (std::vector<std::string>{"one", "two", "", "three", std::string(20, 'x'), "four"}))
        << chunk;
    EXPECT_EQ(cut, (std::vector<bool>{false, false, false, false, true, false})) << chunk;
    EXPECT_EQ(lines.error(), "");
  }
}

TEST(LineReader, ManyLinesCrossTheReadersBlocks) {
  // Far more than the reader's block: lines straddle every refill.
  std::string text;
  for (int i = 0; i < 100000; ++i) text += std::to_string(i) + (i % 3 ? "\n" : "\r\n");
  std::istringstream in(text);
  LineReader lines(in, 16);
  std::string_view line;
  int n = 0;
  bool all_match = true;
  while (lines.next(&line)) all_match = all_match && line == std::to_string(n++);
  EXPECT_TRUE(all_match);
  EXPECT_EQ(n, 100000);
  EXPECT_EQ(lines.line_number(), 100000);
}

TEST(Excerpt, QuotesAtMost64BytesAndEscapesControlBytes) {
  EXPECT_EQ(excerpt("VehicleSpeed"), "VehicleSpeed");
  EXPECT_EQ(excerpt("°/s"), "°/s");  // UTF-8 stays as it is
  EXPECT_EQ(excerpt(std::string("a\0b\x7f\xff", 5)), "a\\x00b\\x7F\\xFF");
  const std::string huge(50'000'000, 'A');
  EXPECT_EQ(excerpt(huge), std::string(64, 'A') + "... (50000000 bytes)");
}

}  // namespace
}  // namespace vmass::io

// Files from many hands, read bounded: a directory, a FIFO without a writer, /dev/zero, an
// oversized file and a read error each give a message naming the path and why (and a FIFO does
// not block); lines are cut at their bound; excerpts quote at most 64 bytes, control bytes
// escaped.
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <fstream>
#include <sstream>
#include <string>

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

TEST(Excerpt, QuotesAtMost64BytesAndEscapesControlBytes) {
  EXPECT_EQ(excerpt("VehicleSpeed"), "VehicleSpeed");
  EXPECT_EQ(excerpt("°/s"), "°/s");  // UTF-8 stays as it is
  EXPECT_EQ(excerpt(std::string("a\0b\x7f\xff", 5)), "a\\x00b\\x7F\\xFF");
  const std::string huge(50'000'000, 'A');
  EXPECT_EQ(excerpt(huge), std::string(64, 'A') + "... (50000000 bytes)");
}

}  // namespace
}  // namespace vmass::io

// Every CAN log format is read as boundedly as the candump reader (vmass_io): a directory or a
// device is refused when opened, naming the path and why; a line longer than the bound is one
// corrupt line, the frames around it read; a read error ends the log with problem() saying so,
// never a clean end; a FIFO (candump -l | vmassd --replay FIFO) is read, its format found from
// its first line.
#include "vmass/runtime/log_frame_source.hpp"

#include <sys/stat.h>

#include <cstdlib>
#include <fstream>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "vmass/runtime/text_log_frame_source.hpp"

namespace vmass::runtime {
namespace {

class LogFrameSourceTest : public ::testing::Test {
 protected:
  void SetUp() override {
    char name[] = "/tmp/vmass_log_source_XXXXXX";
    ASSERT_NE(mkdtemp(name), nullptr);
    dir_ = name;
  }
  void TearDown() override { std::system(("rm -rf '" + dir_ + "'").c_str()); }
  std::string dir_;
};

/// Reads the source to its end: the frames' ids and the corrupt lines' messages.
void read_all(LogFrameSource* source, std::vector<std::uint32_t>* ids,
              std::vector<std::string>* corrupt) {
  source->on_error([corrupt](const can::CandumpError& e) { corrupt->push_back(e.message); });
  can::CanFrame frame;
  while (source->read(&frame, 0) == FrameSource::Read::kFrame) ids->push_back(frame.id);
}

TEST_F(LogFrameSourceTest, DirectoriesAndDevicesAreRefusedWhenOpened) {
  std::string error;
  EXPECT_EQ(open_log_frame_source(dir_, &error), nullptr);
  EXPECT_EQ(error, dir_ + ": cannot open the log: is a directory");
  EXPECT_EQ(open_log_frame_source("/dev/zero", &error), nullptr);
  EXPECT_EQ(error, "/dev/zero: cannot open the log: is a character device");
}

TEST_F(LogFrameSourceTest, AnOverlongLineIsOneCorruptLine) {
  const std::string path = dir_ + "/drive.log";
  std::ofstream(path) << "(1.000000) can0 123#11\n"
                      << "(1.010000) can0 124#" << std::string(10000, '2') << "\n"
                      << "(1.020000) can0 125#33\n";
  std::string error;
  std::unique_ptr<LogFrameSource> source = open_log_frame_source(path, &error);
  ASSERT_NE(source, nullptr) << error;
  std::vector<std::uint32_t> ids;
  std::vector<std::string> corrupt;
  read_all(source.get(), &ids, &corrupt);
  EXPECT_EQ(ids, (std::vector<std::uint32_t>{0x123, 0x125}));
  ASSERT_EQ(corrupt.size(), 1u);
  EXPECT_EQ(corrupt[0], path + ":2: line longer than 4096 bytes");
  EXPECT_EQ(source->stats().lines, 3u);
  EXPECT_EQ(source->problem(), "");
}

TEST_F(LogFrameSourceTest, AReadErrorIsNotTheEndOfTheLog) {
  // Reading a directory through a file stream fails with EISDIR on the first read.
  auto in = std::make_unique<std::ifstream>(dir_, std::ios::binary);
  ASSERT_TRUE(in->is_open());
  std::string error;
  std::unique_ptr<TextLogFrameSource> source =
      TextLogFrameSource::from_stream(std::move(in), "stdin", true, &error);
  ASSERT_NE(source, nullptr) << error;
  can::CanFrame frame;
  EXPECT_EQ(source->read(&frame, 0), FrameSource::Read::kEnd);
  EXPECT_EQ(source->problem(), "stdin: read error: Is a directory");
}

TEST_F(LogFrameSourceTest, AFifoIsReadItsFormatFromItsFirstLine) {
  const std::string fifo = dir_ + "/live.log";
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  std::thread writer(
      [&fifo] { std::ofstream(fifo) << "\n(1.000000) can0 123#11\n(1.010000) can0 124#22\n"; });
  std::string error;
  std::unique_ptr<LogFrameSource> source = open_log_frame_source(fifo, &error);
  ASSERT_NE(source, nullptr) << error;
  std::vector<std::uint32_t> ids;
  std::vector<std::string> corrupt;
  read_all(source.get(), &ids, &corrupt);
  writer.join();
  EXPECT_EQ(source->format(), can::LogFormat::kCandump);
  EXPECT_EQ(ids, (std::vector<std::uint32_t>{0x123, 0x124}));
  EXPECT_TRUE(corrupt.empty());
  EXPECT_EQ(source->problem(), "");
}

}  // namespace
}  // namespace vmass::runtime

// One interface of a multi-interface log (LogFrameSource::select_interface, every format): a
// candump -l log with can0, can1 and vcan2, an ASC with two channels and a TRC with two buses
// (channel N is can<N-1>) give the frames of the selected interface alone, the others skipped
// and counted, never as corrupt; without a selection every frame comes through; a name the log
// does not have is answered with those it has; a name no interface can have is refused.
#include "vmass/runtime/interface_selection.hpp"

#include <cstdlib>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "vmass/runtime/log_frame_source.hpp"

namespace vmass::runtime {
namespace {

constexpr const char* kCandump =
    "(1.000000) can0 123#01\n"
    "(1.001000) can1 124#02\n"
    "(1.002000) vcan2 125#03\n"
    "(1.003000) can1 126#04\n"
    "(1.004000) can0 127#05\n";

constexpr const char* kAsc =
    "date Wed Jan 10 10:55:25.123 am 2024\n"
    "base hex  timestamps absolute\n"
    "internal events logged\n"
    "Begin Triggerblock Wed Jan 10 10:55:25.123 am 2024\n"
    "   0.000000 Start of measurement\n"
    "   0.010000 1  123             Rx   d 1 01\n"
    "   0.011000 2  124             Rx   d 1 02\n"
    "   0.020000 1  125             Rx   d 1 03\n"
    "   0.021000 2  126             Rx   d 1 04\n"
    "   0.022000 2  127             Rx   d 1 05\n"
    "End TriggerBlock\n";

constexpr const char* kTrc =
    ";$FILEVERSION=2.1\n"
    ";$STARTTIME=45301.4550115741\n"
    ";$COLUMNS=N,O,T,B,I,d,R,L,D\n"
    "      1       10.000 DT  1     0123 Rx -  1    01\n"
    "      2       11.000 DT  2     0124 Rx -  1    02\n"
    "      3       20.000 DT  1     0125 Rx -  1    03\n"
    "      4       21.000 DT  2     0126 Rx -  1    04\n"
    "      5       22.000 DT  2     0127 Rx -  1    05\n";

class InterfaceSelectionTest : public ::testing::Test {
 protected:
  void SetUp() override {
    char name[] = "/tmp/vmass_interface_XXXXXX";
    ASSERT_NE(mkdtemp(name), nullptr);
    dir_ = name;
  }
  void TearDown() override { std::system(("rm -rf '" + dir_ + "'").c_str()); }

  /// The log `text` written as `name`, opened.
  std::unique_ptr<LogFrameSource> open(const std::string& name, const std::string& text) {
    const std::string path = dir_ + "/" + name;
    std::ofstream(path, std::ios::binary) << text;
    std::string error;
    std::unique_ptr<LogFrameSource> source = open_log_frame_source(path, &error);
    EXPECT_NE(source, nullptr) << error;
    return source;
  }
  std::string dir_;
};

struct Read {
  std::vector<std::uint32_t> ids;
  std::vector<std::string> interfaces;
  std::vector<std::string> corrupt;
};

Read read_all(LogFrameSource& source) {
  Read r;
  source.on_error([&r](const can::CandumpError& e) { r.corrupt.push_back(e.message); });
  can::CanFrame frame;
  while (source.read(&frame, 0) == FrameSource::Read::kFrame) {
    r.ids.push_back(frame.id);
    r.interfaces.emplace_back(source.interface_name());
  }
  return r;
}

using Ids = std::vector<std::uint32_t>;
using Names = std::vector<std::string>;

TEST(InterfaceName, OneToFifteenOfLettersDigitsAndUnderscoreDotDash) {
  for (const char* good : {"can0", "can1", "vcan2", "c", "can_fd.2-x", "abcdefghijklmno"}) {
    EXPECT_EQ(InterfaceSelection::name_error(good), "") << good;
  }
  const std::string rule =
      "an interface name has 1 to 15 characters of A-Z a-z 0-9 _ . - (e.g. can1)";
  EXPECT_EQ(InterfaceSelection::name_error(""), "empty: " + rule);
  EXPECT_EQ(InterfaceSelection::name_error("abcdefghijklmnop"),
            "'abcdefghijklmnop' is too long: " + rule);
  EXPECT_EQ(InterfaceSelection::name_error("can 1"), "'can 1': " + rule);
  for (const char* bad : {"can/1", "can:1", "can\n1", "c\xc3\xa4n", "*", "can1 "}) {
    EXPECT_NE(InterfaceSelection::name_error(bad), "") << bad;
  }
}

TEST_F(InterfaceSelectionTest, WithoutASelectionEveryFrameComesThrough) {
  std::unique_ptr<LogFrameSource> source = open("drive.log", kCandump);
  ASSERT_NE(source, nullptr);
  const Read r = read_all(*source);
  EXPECT_EQ(r.ids, (Ids{0x123, 0x124, 0x125, 0x126, 0x127}));
  EXPECT_EQ(r.interfaces, (Names{"can0", "can1", "vcan2", "can1", "can0"}));
  EXPECT_EQ(source->stats().frames, 5u);
  EXPECT_EQ(source->interface_selection(), nullptr);
  EXPECT_EQ(source->no_frames_reason(), "");
}

TEST_F(InterfaceSelectionTest, ACandumpLogGivesTheSelectedInterfaceAlone) {
  std::unique_ptr<LogFrameSource> source = open("drive.log", kCandump);
  ASSERT_NE(source, nullptr);
  source->select_interface("can1");
  const Read r = read_all(*source);
  EXPECT_EQ(r.ids, (Ids{0x124, 0x126}));
  EXPECT_EQ(r.interfaces, (Names{"can1", "can1"}));
  EXPECT_TRUE(r.corrupt.empty());
  EXPECT_EQ(source->stats().frames, 2u);  // on can1
  EXPECT_EQ(source->stats().lines, 5u);
  EXPECT_EQ(source->stats().corrupt, 0u);
  EXPECT_EQ(source->position(), 4);  // the line of the last frame read
  ASSERT_NE(source->interface_selection(), nullptr);
  EXPECT_EQ(source->interface_selection()->name(), "can1");
  EXPECT_EQ(source->interface_selection()->skipped(), 3u);
  EXPECT_EQ(source->no_frames_reason(), "");
}

TEST_F(InterfaceSelectionTest, AscChannelTwoIsCan1) {
  std::unique_ptr<LogFrameSource> source = open("drive.asc", kAsc);
  ASSERT_NE(source, nullptr);
  EXPECT_EQ(source->format(), can::LogFormat::kAsc);
  source->select_interface("can1");
  const Read r = read_all(*source);
  EXPECT_EQ(r.ids, (Ids{0x124, 0x126, 0x127}));
  EXPECT_TRUE(r.corrupt.empty());
  EXPECT_EQ(source->interface_selection()->skipped(), 2u);
  EXPECT_EQ(source->stats().corrupt, 0u);
}

TEST_F(InterfaceSelectionTest, TrcBusOneIsCan0) {
  std::unique_ptr<LogFrameSource> source = open("drive.trc", kTrc);
  ASSERT_NE(source, nullptr);
  EXPECT_EQ(source->format(), can::LogFormat::kTrc);
  source->select_interface("can0");
  const Read r = read_all(*source);
  EXPECT_EQ(r.ids, (Ids{0x123, 0x125}));
  EXPECT_TRUE(r.corrupt.empty());
  EXPECT_EQ(source->interface_selection()->skipped(), 3u);
}

TEST_F(InterfaceSelectionTest, ANameTheLogDoesNotHaveIsAnsweredWithThoseItHas) {
  std::unique_ptr<LogFrameSource> source = open("drive.log", kCandump);
  ASSERT_NE(source, nullptr);
  source->select_interface("can2");
  const Read r = read_all(*source);
  EXPECT_TRUE(r.ids.empty());
  EXPECT_TRUE(r.corrupt.empty());
  EXPECT_EQ(source->no_frames_reason(),
            dir_ +
                "/drive.log: no frame on interface can2; the log has can0 (2 frames), can1 (2 "
                "frames), vcan2 (1 frame)");

  std::unique_ptr<LogFrameSource> asc = open("drive.asc", kAsc);
  ASSERT_NE(asc, nullptr);
  asc->select_interface("can2");
  read_all(*asc);
  EXPECT_EQ(asc->no_frames_reason(),
            dir_ +
                "/drive.asc: no frame on interface can2; the log has can0 (2 frames), can1 (3 "
                "frames)");
}

TEST_F(InterfaceSelectionTest, ALogWithoutAFrameSaysSo) {
  std::unique_ptr<LogFrameSource> empty = open("empty.log", "");
  ASSERT_NE(empty, nullptr);
  empty->select_interface("can0");
  read_all(*empty);
  EXPECT_EQ(empty->no_frames_reason(),
            dir_ + "/empty.log: no frame on interface can0; the log has no frame");
  // Not one line could be read: that is what is wrong, whatever the interface.
  std::unique_ptr<LogFrameSource> corrupt = open("corrupt.log", "(1.000000) can0 12X#00\n");
  ASSERT_NE(corrupt, nullptr);
  corrupt->select_interface("can0");
  const Read r = read_all(*corrupt);
  EXPECT_EQ(r.corrupt.size(), 1u);
  EXPECT_EQ(corrupt->no_frames_reason().find(dir_ + "/corrupt.log: no frames: 1 of 1 lines"), 0u)
      << corrupt->no_frames_reason();
}

TEST(InterfaceSelection, CountsTheFirst32OtherInterfacesOneByOne) {
  InterfaceSelection selection("can99");
  for (int i = 0; i < 40; ++i) EXPECT_FALSE(selection.take("can" + std::to_string(i)));
  EXPECT_FALSE(selection.take("can0"));
  EXPECT_TRUE(selection.take("can99"));
  EXPECT_EQ(selection.skipped(), 41u);
  const std::string reason = selection.none_taken_reason();
  EXPECT_EQ(reason.find("no frame on interface can99; the log has can0 (2 frames), can1 (1 "
                        "frame), "),
            0u)
      << reason;
  EXPECT_NE(reason.find(", can31 (1 frame), and 8 frames on more interfaces"), std::string::npos)
      << reason;
}

}  // namespace
}  // namespace vmass::runtime

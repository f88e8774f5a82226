// The daemon's CAN input path with what the CAN layer has today: frames from a candump log or a
// SocketCAN reader (through its fd seam), classified against a real DBC by DecodeOnlyMapper.
// The signal mapping (can.inputs -> estimator inputs) is not wired yet: inputs stay invalid.
#include <linux/can.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>
#include <lcm/lcm-cpp.hpp>
#include <vmass/mass_estimate_t.hpp>
#include <vmass/status_t.hpp>

#include "test_drive.hpp"
#include "vmass/can/dbc.hpp"
#include "vmass/service/can_input_source.hpp"

namespace vmass::service {
namespace {

namespace fs = std::filesystem;
const std::string kDbc = std::string(VMASS_SOURCE_DIR) + "/tests/data/dbc/toyota_prius_2010_pt.dbc";

can::Decoder prius() {
  can::DbcParseResult r = can::load_dbc_file(kDbc);
  EXPECT_TRUE(r.ok());
  std::string error;
  std::optional<can::Decoder> d = can::Decoder::compile(std::move(r.database), &error);
  EXPECT_TRUE(d.has_value()) << error;
  return std::move(*d);
}

/// A log with 100 SPEED frames (0xB4, 8 bytes), 10 of an id not in the DBC, 5 SPEED frames
/// too short, 1 error frame and 2 corrupt lines.
std::string write_log(const std::string& path) {
  std::ofstream out(path);
  long t_us = 0;
  auto stamp = [&] {
    char buf[32];
    std::snprintf(buf, sizeof buf, "(%ld.%06ld)", 1700000000L + t_us / 1000000, t_us % 1000000);
    t_us += 10000;
    return std::string(buf);
  };
  for (int i = 0; i < 100; ++i) out << stamp() << " can0 0B4#0000000000001000\n";
  for (int i = 0; i < 10; ++i) out << stamp() << " can0 7FF#0102\n";
  for (int i = 0; i < 5; ++i) out << stamp() << " can0 0B4#0000\n";
  out << stamp() << " can0 20000004#0000000000000000\n";  // CAN_ERR_FLAG | CAN_ERR_CRTL
  out << stamp() << " can0 XYZ#00\n";
  out << "not a candump line\n";
  return path;
}

TEST(CanInputSource, CandumpLogFramesAreClassifiedAndCounted) {
  const can::Decoder decoder = prius();
  const std::string log =
      write_log(fs::temp_directory_path() / ("vmass_can_" + std::to_string(::getpid()) + ".log"));
  std::string error;
  auto frames = CandumpFrameSource::open(log, &error);
  ASSERT_TRUE(frames) << error;
  CanInputSource source(std::move(frames), std::make_unique<DecodeOnlyMapper>(decoder));
  EXPECT_TRUE(source.recorded());
  InputValues values;
  int records = 0;
  TimeUs last = -1;
  while (source.read(0) == InputSource::Read::kRecord) {
    EXPECT_GT(source.record_time_us(), last);
    last = source.record_time_us();
    source.apply(&values);
    ++records;
  }
  EXPECT_EQ(records, 116);
  const SourceCounters& c = source.counters();
  EXPECT_EQ(c.received.load(), 118);  // frames + corrupt lines
  EXPECT_EQ(c.decoded.load(), 100);
  EXPECT_EQ(c.unknown.load(), 10);
  EXPECT_EQ(c.malformed.load(), 7);  // 5 too short + 2 corrupt lines
  EXPECT_EQ(c.bus_errors.load(), 1);
  EXPECT_EQ(source.health().state, SourceState::kEnded);
  EXPECT_EQ(values.latest.valid, 0u);  // nothing mapped to inputs yet
  EXPECT_EQ(values.updates, 100u);
  fs::remove(log);
}

TEST(CanInputSource, SocketCanReaderThroughItsFdSeam) {
  const can::Decoder decoder = prius();
  int fds[2];
  ASSERT_EQ(::socketpair(AF_UNIX, SOCK_SEQPACKET, 0, fds), 0);
  auto reader = std::make_unique<can::SocketCanReader>(fds[0], can::SocketCanReader::Opener{});
  CanInputSource source(std::make_unique<SocketCanFrameSource>(std::move(reader), "seam0"),
                        std::make_unique<DecodeOnlyMapper>(decoder));
  EXPECT_FALSE(source.recorded());
  EXPECT_EQ(source.describe(), "socketcan:seam0");
  can_frame f{};
  f.can_id = 0xB4;
  f.can_dlc = 8;
  ASSERT_EQ(::write(fds[1], &f, sizeof f), static_cast<ssize_t>(sizeof f));
  f.can_id = 0x7FF;
  ASSERT_EQ(::write(fds[1], &f, sizeof f), static_cast<ssize_t>(sizeof f));
  const char junk[5] = {1, 2, 3, 4, 5};  // a record of a bad size
  ASSERT_EQ(::write(fds[1], junk, sizeof junk), 5);
  InputValues values;
  EXPECT_EQ(source.read(1000), InputSource::Read::kRecord);
  source.apply(&values);
  EXPECT_EQ(source.read(1000), InputSource::Read::kRecord);
  source.apply(&values);
  EXPECT_EQ(source.read(50), InputSource::Read::kTimeout);  // the junk is counted, not returned
  EXPECT_EQ(source.counters().decoded.load(), 1);
  EXPECT_EQ(source.counters().unknown.load(), 1);
  EXPECT_EQ(source.counters().malformed.load(), 1);
  ::close(fds[1]);
  EXPECT_EQ(source.read(1000), InputSource::Read::kEnd);
}

#ifdef VMASSD_BIN
TEST(CanInputSource, VmassdReplaysACandumpLogAndReportsTheCounters) {
  const fs::path dir =
      fs::temp_directory_path() / ("vmassd_can_replay_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const std::string log = write_log((dir / "drive.log").string());
  const std::string config = (dir / "vmassd.yaml").string();
  ASSERT_TRUE(test::write_text(config, test::test_config_yaml("can:\n  dbc: " + kDbc + "\n")));
  const std::string out = (dir / "out.lcm").string();
  const int status = std::system((std::string(VMASSD_BIN) + " --config " + config + " --replay " +
                                  log + " --speed max --no-restore --lcm-url 'file://" + out +
                                  "?mode=w' 2> " + (dir / "err.txt").string())
                                     .c_str());
  ASSERT_TRUE(WIFEXITED(status));
  ASSERT_EQ(WEXITSTATUS(status), 0);
  lcm::LogFile file(out, "r");
  vmass::status_t last;
  long estimates = 0, degraded = 0;
  while (const lcm::LogEvent* ev = file.readNextEvent()) {
    if (ev->channel == "VMASS_STATUS") {
      ASSERT_EQ(last.decode(ev->data, 0, ev->datalen), ev->datalen);
    } else if (ev->channel == "VMASS_ESTIMATE") {
      vmass::mass_estimate_t e;
      ASSERT_EQ(e.decode(ev->data, 0, ev->datalen), ev->datalen);
      ++estimates;
      degraded += e.status_name == "degraded";
    }
  }
  EXPECT_EQ(last.state_name, "stopping");
  EXPECT_EQ(last.source, "replay:" + log);
  EXPECT_EQ(last.frames_received, 118);
  EXPECT_EQ(last.frames_decoded, 100);
  EXPECT_EQ(last.frames_unknown, 10);
  EXPECT_EQ(last.frames_malformed, 7);
  EXPECT_EQ(last.bus_errors, 1);
  // Ticks span the log's time (116 frames, 10 ms apart) in log time.
  EXPECT_EQ(estimates, 116);
  EXPECT_EQ(degraded, estimates);  // no input mapped: honestly degraded
  fs::remove_all(dir);
}
#endif

}  // namespace
}  // namespace vmass::service

// vmassd against the faults of issue 11, as a process: a stop signal while start-up is blocked
// (a FIFO as the log: the open waits for a writer), a FIFO at the state path, an absurd --speed,
// and an LCM URL nothing can be published to (counted, logged at a bounded rate, exit 1).
#include <sys/stat.h>

#include <csignal>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "daemon_process.hpp"
#include "test_dbc.hpp"

namespace vmass {
namespace {

using DaemonFaultTest = test::DaemonProcessTest;

const std::string kVmassd = VMASSD_BIN;

int count_lines(const std::string& text) {
  int n = 0;
  for (char c : text) n += c == '\n';
  return n;
}

TEST_F(DaemonFaultTest, AStopSignalEndsABlockedStartUpAtOnce) {
  ASSERT_TRUE(test::write_text(path("test.dbc"), testing::kTestDbc));
  const std::string config = write_config(
      "can:\n  dbc: test.dbc\n  inputs:\n    speed: {message: Speeds, signal: SpeedKmh}\n");
  const std::string fifo = path("drive.log");
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  // Opening a FIFO for reading waits for a writer: start-up blocks there, with no writer ever.
  start(kVmassd + " --config " + config + " --replay " + fifo + " --lcm-url memq://", "d");
  sleep_s(0.5);
  ASSERT_EQ(wait_rc("d", 0.0), -1) << read("d.log");  // still blocked
  ASSERT_EQ(run("kill -TERM $(cat " + path("d.pid") + ")"), 0);
  EXPECT_EQ(wait_rc("d", 5.0), 0) << read("d.log");
  EXPECT_NE(read("d.log").find("vmassd: stopped during start-up"), std::string::npos);
}

TEST_F(DaemonFaultTest, AFifoAtTheStatePathIsRefusedWithoutBlocking) {
  const std::string state = path("vmassd.state");
  ASSERT_EQ(mkfifo(state.c_str(), 0600), 0);
  const std::string config = write_config("");
  start(kVmassd + " --config " + config + " --samples " + csv_ +
            " --speed max --lcm-url memq:// --state-file " + state,
        "d");
  ASSERT_EQ(wait_rc("d", 60.0), 0) << read("d.log");
  EXPECT_NE(read("d.log").find(state + ": cannot read the state file: is a FIFO (named pipe)"),
            std::string::npos)
      << read("d.log");
  struct stat st {};
  ASSERT_EQ(::stat(state.c_str(), &st), 0);
  EXPECT_TRUE(S_ISREG(st.st_mode));  // the final save replaced it with a state file
}

TEST_F(DaemonFaultTest, SpeedIsBoundedBothWays) {
  const std::string config = write_config("");
  for (const char* speed : {"1e-300", "0", "-1", "1e6", "nan"}) {
    const int rc = run(kVmassd + " --config " + config + " --samples " + csv_ + " --speed " +
                       speed + " --lcm-url memq:// > " + path("out.log") + " 2>&1");
    EXPECT_EQ(rc, 2) << speed;
    EXPECT_NE(read("out.log").find("--speed: expected a factor in [0.001, 1000] or 'max'"),
              std::string::npos)
        << speed << ": " << read("out.log");
  }
}

TEST_F(DaemonFaultTest, NothingPublishedIsAFailureLoggedAtABoundedRate) {
  const std::string config = write_config("");
  // Port 1 of the loopback refuses every connection: each publish fails.
  const int rc = run(kVmassd + " --config " + config + " --samples " + csv_ +
                     " --speed max --lcm-url tcpq://127.0.0.1:1 > " + path("out.log") + " 2>&1");
  const std::string log = read("out.log");
  EXPECT_EQ(rc, 1) << log;
  EXPECT_NE(log.find("nothing was published on LCM: all "), std::string::npos) << log;
  EXPECT_NE(log.find("LCM publish on tcpq://127.0.0.1:1 failed; retrying with backoff"),
            std::string::npos)
      << log;
  // 6000 ticks to publish: the backoff keeps LCM's and our lines to a few dozen.
  EXPECT_LT(count_lines(log), 100) << log;
}

}  // namespace
}  // namespace vmass

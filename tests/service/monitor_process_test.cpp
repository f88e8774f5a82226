// vmass-monitor when vmassd dies (issue 32): in a private network namespace (nothing leaves the
// machine), vmassd replays at real speed with two monitors listening, then is SIGKILLed. The
// --count monitor ends with exit 1 a silence limit (3 s) later, saying why; the plain live view
// goes on, its rates falling to 0 and its report saying that no estimate came for 10 s.
//
// vmass-ctl with the real vmassd (issue 30), in a namespace too: new tyres are accepted (exit 0,
// vmassd's words), a known mass after them too, an absurd mass refused (exit 1); the monitor
// shows the datasheet scale before, then the declared mass and vmassd's last answer.
#include <cstdio>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "daemon_process.hpp"

namespace vmass {
namespace {

using MonitorProcessTest = test::DaemonProcessTest;

/// The header line of each report ("vmass-monitor URL   estimates 100.1 Hz ...").
std::vector<std::string> report_headers(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream lines(text);
  std::string line;
  while (std::getline(lines, line)) {
    if (line.rfind("vmass-monitor ", 0) == 0) out.push_back(line);
  }
  return out;
}

double estimate_rate(const std::string& header) {
  std::smatch m;
  const std::regex rate("estimates ([0-9.]+) Hz");
  return std::regex_search(header, m, rate) ? std::stod(m[1].str()) : -1.0;
}

TEST_F(MonitorProcessTest, SaysVmassdIsGoneAndCountModeFailsAfterASigkill) {
  if (run("unshare -n true 2> /dev/null") != 0) {
    GTEST_SKIP() << "unshare -n not permitted here (needs root or user namespaces)";
  }
  const std::string config = write_config("lcm:\n  url: \"udpm://239.255.76.67:7667?ttl=0\"\n");
  const std::string monitor = std::string(VMASS_MONITOR_BIN) + " --config " + config;
  const std::string script = path("netns.sh");
  ASSERT_TRUE(test::write_text(
      script,
      "set -e\n"
      "ip link set lo up\n"
      "ip route add 224.0.0.0/4 dev lo\n" +
          std::string(VMASSD_BIN) + " --config " + config + " --samples " + csv_ +
          " --no-restore > " + path("daemon.log") +
          " 2>&1 &\n"
          "daemon=$!\n" +
          monitor + " --count 100000000 --plain > " + path("count.txt") + " 2> " +
          path("count.err") +
          " &\n"
          "counter=$!\n" +
          monitor + " --plain --interval 1 > " + path("live.txt") +
          " 2>&1 &\n"
          "live=$!\n"
          "sleep 4\n"
          "kill -KILL $daemon\n"
          "killed=$(date +%s.%N)\n"
          "set +e\n"
          "wait $counter\n"
          "counted=$?\n"
          "ended=$(date +%s.%N)\n"
          "sleep 9\n"
          "kill -TERM $live\n"
          "wait $live\n"
          "echo \"$counted $(awk -v a=$killed -v b=$ended 'BEGIN { print b - a }')\"\n"));
  FILE* out = ::popen(("unshare -n sh " + script + " 2>&1").c_str(), "r");
  ASSERT_NE(out, nullptr);
  int count_rc = -1;
  double after_s = -1.0;
  const int fields = std::fscanf(out, "%d %lf", &count_rc, &after_s);
  ASSERT_EQ(::pclose(out), 0);
  ASSERT_EQ(fields, 2) << read("daemon.log");

  // --count: exit 1 once no estimate came for the silence limit (3 s here), and says why.
  EXPECT_EQ(count_rc, 1) << read("count.err") << read("count.txt");
  EXPECT_GT(after_s, 2.5) << read("count.err");
  EXPECT_LT(after_s, 8.0) << read("count.err");  // 3 s, and the load of a shared machine
  EXPECT_TRUE(std::regex_search(read("count.err"),
                                std::regex("vmass-monitor: no estimate for [3-7] s: is vmassd "
                                           "running\\? \\(last status [0-9]+ s ago\\)")))
      << read("count.err");

  // The live view: 100 Hz while vmassd ran, 0 at its last report (more than 10 s after the
  // kill: the rates are the last 5 s's), which says so.
  const std::string live = read("live.txt");
  const std::vector<std::string> headers = report_headers(live);
  ASSERT_GE(headers.size(), 10u) << live;
  EXPECT_NEAR(estimate_rate(headers[2]), 100.0, 10.0) << headers[2];
  EXPECT_EQ(estimate_rate(headers.back()), 0.0) << headers.back();
  const std::string last_report = live.substr(live.rfind("vmass-monitor "));
  EXPECT_NE(last_report.find("status 0.00 Hz"), std::string::npos) << last_report;
  EXPECT_TRUE(
      std::regex_search(last_report, std::regex("\nSILENT +no estimate for 1[0-9] s: is vmassd "
                                                "running\\?")))
      << last_report;
  EXPECT_NE(last_report.find("daemon    running"), std::string::npos) << last_report;
}

TEST_F(MonitorProcessTest, ShowsWhatVmassCtlToldVmassd) {
  if (run("unshare -n true 2> /dev/null") != 0) {
    GTEST_SKIP() << "unshare -n not permitted here (needs root or user namespaces)";
  }
  const std::string config = write_config("lcm:\n  url: \"udpm://239.255.76.67:7667?ttl=0\"\n");
  const std::string monitor =
      std::string(VMASS_MONITOR_BIN) + " --config " + config + " --once --timeout 10 > ";
  const std::string ctl = std::string(VMASS_CTL_BIN) + " --config " + config;
  const std::string script = path("netns.sh");
  ASSERT_TRUE(test::write_text(
      script,
      "ip link set lo up\n"
      "ip route add 224.0.0.0/4 dev lo\n" +
          std::string(VMASSD_BIN) + " --config " + config + " --samples " + csv_ +
          " --no-restore > " + path("daemon.log") +
          " 2>&1 &\n"
          "daemon=$!\n" +
          monitor + path("before.txt") + " 2>&1\n" + ctl + " tyres-changed > " + path("tyres.txt") +
          " 2>&1\n"
          "echo $? > " +
          path("tyres.rc") + "\n" + ctl + " known-mass 1800 --note 'monitor process test' > " +
          path("known.txt") +
          " 2>&1\n"
          "echo $? > " +
          path("known.rc") + "\n" + ctl + " known-mass 99999 > " + path("absurd.txt") +
          " 2>&1\n"
          "echo $? > " +
          path("absurd.rc") + "\n" + monitor + path("after.txt") +
          " 2>&1\n"
          "kill -TERM $daemon\n"
          "wait $daemon\n"));
  ASSERT_EQ(run("unshare -n sh " + script), 0) << read("daemon.log");

  const std::string before = read("before.txt");
  EXPECT_NE(before.find("\nlearnt    scale: datasheet (no known mass yet)\n"), std::string::npos)
      << before;
  EXPECT_EQ(before.find("\ncommand "), std::string::npos) << before;
  EXPECT_EQ(read("known.rc"), "0\n") << read("known.txt") << read("daemon.log");
  EXPECT_EQ(read("known.txt"),
            "vmassd: accepted: known mass 1800.0 kg (std 9.0 kg) from the next tick\n");
  EXPECT_EQ(read("tyres.rc"), "0\n") << read("tyres.txt");
  EXPECT_EQ(read("tyres.txt").rfind("vmassd: accepted: new tyres - the learnt scale widens ", 0),
            0u)
      << read("tyres.txt");
  EXPECT_EQ(read("absurd.rc"), "1\n") << read("absurd.txt");
  EXPECT_EQ(read("absurd.txt").rfind("vmassd: refused: known mass 99999.0 kg ", 0), 0u)
      << read("absurd.txt");
  const std::string after = read("after.txt");
  EXPECT_TRUE(std::regex_search(after, std::regex("\nmass      1800.0 kg   known \\(declared\\)")))
      << after;
  EXPECT_TRUE(std::regex_search(after, std::regex("\ncommand   refused: known mass 99999.0 kg "
                                                  "[^]*\\([0-9] s ago\\)\n")))
      << after;
}

}  // namespace
}  // namespace vmass

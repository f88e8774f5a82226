// status_t carries the bus's health (issue 11's telemetry): vmassd replays the simulator's
// sensor_faults drive of compact-11, with the simulator's E2E protection declared and a frozen
// ESC_Speed frame, a pair of frames swapped in time and one frame stamped years ahead added to
// the log; its last VMASS_STATUS has per-input stale, implausible and counter-fail counts, the
// watched messages with their E2E and timing counts and validity, the bus-valid flag and the
// input clock's counts.
#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>
#include <lcm/lcm-cpp.hpp>
#include <vmass/status_t.hpp>

#include <algorithm>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "daemon_process.hpp"

namespace vmass {
namespace {

using TelemetryTest = test::DaemonProcessTest;

/// The config vmass-sim wrote, with the inputs this estimator reads and can.e2e for every
/// message that has a counter (the simulator's `protect`: XOR of the id's low byte and bytes
/// 0..5 in byte 6, a 4-bit counter in byte 7).
std::string protected_config(const std::string& dir) {
  const YAML::Node inputs = YAML::LoadFile(dir + "/config.yaml")["can"]["inputs"];
  YAML::Node kept(YAML::NodeType::Map);
  for (const auto& kv : inputs) {
    for (int i = 0; i < kInputCount; ++i) {
      if (kv.first.as<std::string>() == input_name(static_cast<Input>(i))) {
        kept[kv.first.as<std::string>()] = kv.second;
      }
    }
  }
  YAML::Emitter flow;
  flow << YAML::Flow << kept;
  std::ifstream dbc(dir + "/vehicle.dbc");
  std::string line, e2e;
  while (std::getline(dbc, line)) {
    const auto at = line.find("_Counter :");
    if (line.rfind(" SG_ ", 0) != 0 || at == std::string::npos) continue;
    const std::string m = line.substr(5, at - 5);
    e2e += (e2e.empty() ? "" : ", ") + m + ": {counter: " + m + "_Counter, checksum: " + m +
           "_Checksum, algorithm: xor, data_id: id_low_byte, bytes: [0, 5]}";
  }
  return "can:\n  dbc: vehicle.dbc\n  e2e: {messages: {" + e2e + "}}\n  inputs: " + flow.c_str() +
         "\n";
}

/// The log with three more lies: ESC_Speed (0x190, every 20 ms) frozen for 0.2 s at 20 s, two
/// frames swapped at 30 s, one frame stamped in 2030.
void tamper(const std::string& in_path, const std::string& out_path) {
  std::ifstream in(in_path);
  std::vector<std::string> lines;
  std::string line;
  while (std::getline(in, line)) lines.push_back(line);
  std::string frozen;
  for (std::string& l : lines) {
    const double t = std::stod(l.substr(1, 17));
    if (l.find(" 190#") == std::string::npos) continue;
    if (t >= 20.0 && t < 20.2) {
      if (frozen.empty()) frozen = l.substr(l.find(' '));
      l = l.substr(0, l.find(' ')) + frozen;  // its time, the first frame's content
    }
  }
  for (std::size_t i = 1; i < lines.size(); ++i) {
    if (std::stod(lines[i].substr(1, 17)) >= 30.0) {
      std::swap(lines[i - 1], lines[i]);
      break;
    }
  }
  lines.insert(lines.begin() + static_cast<long>(lines.size() / 2),
               "(1900000000.000000) can0 7FF#00");
  std::ofstream out(out_path);
  for (const std::string& l : lines) out << l << "\n";
}

TEST_F(TelemetryTest, TheLastStatusCarriesTheBusHealth) {
  ASSERT_EQ(
      run(std::string(VMASS_SIM_BIN) + " --vehicle compact-11 --scenario sensor_faults --out " +
          dir_.string() + " > /dev/null 2>&1"),
      0);
  const std::string config = write_config(protected_config(dir_.string()));
  tamper(path("drive.log"), path("tampered.log"));
  const std::string lcm_log = path("out.lcm");
  ASSERT_EQ(run(std::string(VMASSD_BIN) + " --config " + config + " --replay " +
                path("tampered.log") + " --speed max --no-restore --lcm-url 'file://" + lcm_log +
                "?mode=w' 2> " + path("err.txt")),
            0)
      << read("err.txt");
  lcm::LogFile file(lcm_log, "r");
  vmass::status_t last;
  while (const lcm::LogEvent* ev = file.readNextEvent()) {
    if (ev->channel == "VMASS_STATUS") {
      ASSERT_EQ(last.decode(ev->data, 0, ev->datalen), ev->datalen);
    }
  }
  auto at = [](Input in) { return static_cast<std::size_t>(in); };
  EXPECT_GE(last.input_stale[at(Input::kYawRate)], 1);                   // dynamics missing 40-43 s
  EXPECT_GE(last.input_implausible[at(Input::kSpeed)], 1);               // absurd at 90 s
  EXPECT_GE(last.input_implausible[at(Input::kSteeringWheelAngle)], 1);  // frozen 60-70 s
  EXPECT_GE(last.input_counter_fail[at(Input::kSpeed)], 9);  // 9 repeats (20 ms cycle), 1 jump
  EXPECT_EQ(last.input_checksum_fail[at(Input::kSpeed)], 0);
  EXPECT_EQ(last.input_counter_fail[at(Input::kAccelX)], 0);
  ASSERT_GE(last.num_messages, 6);
  const auto speed = std::find(last.message_name.begin(), last.message_name.end(), "ESC_Speed");
  ASSERT_NE(speed, last.message_name.end());
  const auto s = static_cast<std::size_t>(speed - last.message_name.begin());
  EXPECT_GE(last.message_counter_fail[s], 9);
  EXPECT_TRUE(last.message_valid[s]);  // valid again after the frozen frame
  EXPECT_TRUE(last.bus_valid);
  EXPECT_GE(last.frames_reordered, 1);
  EXPECT_EQ(last.time_jumps, 1);  // the 2030 frame, dropped
  EXPECT_GE(last.frames_unknown, 900);
  EXPECT_EQ(last.input_reason[at(Input::kSpeed)], "");  // valid at the end
  EXPECT_NE(read("err.txt").find("ESC_Speed "), std::string::npos) << read("err.txt");
}

}  // namespace
}  // namespace vmass

// A stand-in for vmassd's command handling, for vmass-ctl's test (ctl_test.sh): it publishes a
// vmass.status_t every 0.2 s on STATUS_CHANNEL and answers each vmass.command_t on
// COMMAND_CHANNEL as MODE says:
//
//   accept   a decoy status first (another command's id, "refused: ..."), then the answer
//            "accepted: ..." in vmassd's words (src/service/daemon_command.cpp)
//   refuse   a decoy ("accepted: ..." for another id), then "refused: ..."
//   deaf     never answers: its statuses go on naming no command (a vmassd that does not read
//            this channel)
//
// Each command received is one line on stdout: "command NAME schema N mass_kg X std_kg Y
// clock_ok 0|1 note TEXT" (clock_ok: its utime is within 10 s of this CLOCK_REALTIME). "ready"
// once subscribed. It ends on SIGTERM or after 60 s.
//
//   fake_vmassd URL COMMAND_CHANNEL STATUS_CHANNEL accept|refuse|deaf
#include <time.h>

#include <chrono>
#include <csignal>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <utility>

#include <lcm/lcm-cpp.hpp>
#include <vmass/command_t.hpp>
#include <vmass/status_t.hpp>

namespace {

volatile std::sig_atomic_t g_stop = 0;
void on_signal(int) { g_stop = 1; }

std::int64_t realtime_us() {
  timespec ts{};
  ::clock_gettime(CLOCK_REALTIME, &ts);
  return static_cast<std::int64_t>(ts.tv_sec) * 1000000 + ts.tv_nsec / 1000;
}

std::string kg(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.1f", v);
  return buf;
}

class Fake {
 public:
  Fake(lcm::LCM& lcm, std::string status_channel, std::string mode)
      : lcm_(lcm), status_channel_(std::move(status_channel)), mode_(std::move(mode)) {}

  void on_command(const lcm::ReceiveBuffer*, const std::string&, const vmass::command_t* c) {
    const std::int64_t age_us = realtime_us() - c->utime;
    std::printf("command %s schema %d mass_kg %.6g std_kg %.6g clock_ok %d note %s\n",
                c->command.c_str(), c->schema_version, c->mass_kg, c->mass_std_kg,
                age_us > -10000000 && age_us < 10000000 ? 1 : 0, c->note.c_str());
    std::fflush(stdout);
    ++commands_;
    if (mode_ == "deaf") return;
    const bool accept = mode_ == "accept";
    // A status answering another command, with the opposite verdict: vmass-ctl must wait on.
    publish(c->utime + 1, accept ? "refused: a decoy for another command"
                                 : "accepted: a decoy for another command");
    std::string answer;
    if (c->command == "reset_learnt") {
      answer = accept ? "accepted: what was learnt about the car is forgotten (back to the "
                        "config's datasheet values)"
                      : "refused: a fake that refuses everything";
    } else if (c->command == "tyres_changed") {
      answer = accept ? "accepted: new tyres - the learnt scale widens by the rolling radius's "
                        "uncertainty"
                      : "refused: a fake that refuses everything";
    } else {
      answer = accept ? "accepted: known mass " + kg(c->mass_kg) + " kg (std " +
                            kg(c->mass_std_kg) + " kg) from the next tick"
                      : "refused: known mass " + kg(c->mass_kg) +
                            " kg is outside the config's plausible band (empty mass to the "
                            "maximum permissible mass)";
    }
    last_utime_ = c->utime;
    last_result_ = answer;
    publish(last_utime_, last_result_);
  }

  /// The periodic status: the last command answered (none: 0).
  void publish_periodic() { publish(last_utime_, last_result_); }

 private:
  void publish(std::int64_t command_utime, const std::string& result) {
    vmass::status_t s{};
    s.utime = realtime_us();
    s.schema_version = 8;  // vmass::service::kLcmSchemaVersion
    s.version = "0.0.0-fake";
    s.state_name = "running";
    s.commands_received = commands_;
    s.last_command_utime = command_utime;
    s.last_command_result = result;
    lcm_.publish(status_channel_, &s);
  }

  lcm::LCM& lcm_;
  std::string status_channel_, mode_;
  std::int64_t commands_ = 0;
  std::int64_t last_utime_ = 0;
  std::string last_result_;
};

}  // namespace

int main(int argc, char** argv) {
  if (argc != 5) {
    std::fprintf(stderr,
                 "usage: fake_vmassd URL COMMAND_CHANNEL STATUS_CHANNEL "
                 "accept|refuse|deaf\n");
    return 2;
  }
  const std::string mode = argv[4];
  if (mode != "accept" && mode != "refuse" && mode != "deaf") {
    std::fprintf(stderr, "fake_vmassd: unknown mode '%s'\n", mode.c_str());
    return 2;
  }
  lcm::LCM lcm(argv[1]);
  if (!lcm.good()) {
    std::fprintf(stderr, "fake_vmassd: cannot open LCM at '%s'\n", argv[1]);
    return 1;
  }
  Fake fake(lcm, argv[3], mode);
  lcm.subscribe(argv[2], &Fake::on_command, &fake);
  std::signal(SIGTERM, on_signal);
  std::signal(SIGINT, on_signal);
  std::printf("ready\n");
  std::fflush(stdout);
  using Clock = std::chrono::steady_clock;
  const Clock::time_point end = Clock::now() + std::chrono::seconds(60);
  Clock::time_point next_status = Clock::now();
  while (!g_stop && Clock::now() < end) {
    if (Clock::now() >= next_status) {
      fake.publish_periodic();
      next_status += std::chrono::milliseconds(200);
    }
    lcm.handleTimeout(20);
  }
  return 0;
}

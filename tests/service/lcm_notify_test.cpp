// LCM publish/subscribe round trip on memq:// (every field as sent, every double finite) and the
// sd_notify protocol through a NOTIFY_SOCKET datagram socket bound by the test (no systemd),
// including no WATCHDOG=1 while vmassd's estimator thread is stalled.
#include <fcntl.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <lcm/lcm-cpp.hpp>

#include "vmass/service/lcm_publisher.hpp"
#include "vmass/service/systemd_notifier.hpp"
#include "vmass/version.hpp"

namespace vmass::service {
namespace {

using runtime::TickRecord;

TickRecord make_record(std::int64_t tick) {
  TickRecord r;
  r.tick = tick;
  Estimate& e = r.estimate;
  e.time_us = 1'700'000'000'000'000 + tick * 10'000;
  e.mass_known = true;
  e.mass_kg = 1712.25 + static_cast<double>(tick);
  e.mu_n = -12.5;
  e.mass_std_kg = 14.0;
  e.ci_low_kg = e.mass_kg - 27.5;
  e.ci_high_kg = e.mass_kg + 27.5;
  e.initial_mass_kg = 1650.0;
  e.pairs_used = 321;
  e.status = EstimateStatus::kConverging;
  e.reason = StatusReason::kRefining;
  e.invalid_inputs = input_bit(Input::kGear);
  e.blocks[0].ticks = 1000;
  e.blocks[0].accepted = 250;
  e.blocks[0].rejected_innovation = 7;
  e.blocks[1].ticks = 1000;
  e.blocks[1].accepted = 71;
  r.events[0].verdict = PairVerdict::kAccepted;
  r.events[0].has_candidate = true;
  r.events[0].pair.y_n = 850.0;
  r.events[0].pair.delta_accel_mps2 = 0.5;
  r.events[0].pair.time_us = e.time_us;
  r.events[0].predicted_y_n = 845.0;
  r.events[0].innovation_variance_n2 = 1.0e4;
  r.events[0].test_ratio = 0.05;
  r.events[0].pair.rotating_n = 21.0;
  r.events[0].pair.rotating_mass_kg = 42.0;
  r.events[0].pair.gear = 3;
  r.events[0].pair.noise_std_n = 60.0;
  r.events[1].verdict = PairVerdict::kSteering;
  r.events[1].predicted_y_n = std::numeric_limits<double>::quiet_NaN();  // never on the wire
  r.inputs_valid = kAllInputs & ~input_bit(Input::kGear);
  for (int i = 0; i < kInputCount; ++i) r.input_age_s[i] = 0.01 * i;
  r.input_age_s[static_cast<int>(Input::kGear)] = -1.0;
  return r;
}

struct Received {
  std::vector<vmass::mass_estimate_t> estimates;
  std::vector<vmass::status_t> statuses;
  std::vector<vmass::pair_t> pairs;
  void on_estimate(const lcm::ReceiveBuffer*, const std::string&, const vmass::mass_estimate_t* m) {
    estimates.push_back(*m);
  }
  void on_status(const lcm::ReceiveBuffer*, const std::string&, const vmass::status_t* m) {
    statuses.push_back(*m);
  }
  void on_pair(const lcm::ReceiveBuffer*, const std::string&, const vmass::pair_t* m) {
    pairs.push_back(*m);
  }
};

void drain(lcm::LCM& lcm) {
  while (lcm.handleTimeout(0) > 0) {
  }
}

TEST(LcmRoundTrip, EstimatePairsAndStatusArriveIntactAndFinite) {
  lcm::LCM lcm("memq://");
  ASSERT_TRUE(lcm.good());
  LcmSettings settings;
  settings.publish_pairs = true;
  Received rx;
  lcm.subscribe(settings.estimate_channel, &Received::on_estimate, &rx);
  lcm.subscribe(settings.status_channel, &Received::on_status, &rx);
  lcm.subscribe(settings.pairs_channel, &Received::on_pair, &rx);

  LcmPublisher publisher(lcm, settings, "bayes");
  const TickRecord record = make_record(3);
  ASSERT_TRUE(publisher.on_tick(record));
  DaemonStatus status;
  status.state = DaemonState::kRunning;
  status.source = "samples:drive.csv";
  status.uptime_s = 12.5;
  status.tick_rate_hz = 100.0;
  status.last = record;
  status.has_tick = true;
  status.frames_received = 1201;
  status.frames_decoded = 1200;
  status.frames_malformed = 1;
  status.timing.ticks = 1250;
  status.timing.overruns = 2;
  status.timing.jitter_p50_us = 15.0;
  status.timing.jitter_p99_us = 240.0;
  status.timing.jitter_max_us = 900.0;
  status.state_restored = true;
  // Schema 3: why no pair (the record's events, five ticks), the learnt scale, a command.
  for (int i = 0; i < 5; ++i) status.verdicts.add(record.events);
  status.last.estimate.learnt_scale = 1.031;
  status.last.estimate.learnt_scale_std = 0.012;
  status.last.estimate.learnt_evidence = 2;
  status.last.estimate.known_mass = true;
  // Schema 5: the learnt rotating masses of three gears.
  status.last.estimate.learnt_gears = 3;
  status.last.estimate.learnt_gear_correction_kg = {-1250.5, -310.25, 12.0};
  status.last.estimate.learnt_gear_std_kg = {400.0, 150.5, 30.25};
  status.last.estimate.learnt_gear_drives = 6;
  status.last.estimate.learnt_anchors = 4;       // schema 6
  status.last.estimate.learnt_tyre_changes = 1;  // schema 7
  status.last.estimate.learnt_evidence_since_tyres = 1;
  Estimate& schema8 = status.last.estimate;  // the tyre watch and the pair-term fit
  schema8.tyre_watch_launches = 7;
  schema8.tyre_watch_stops = 5;
  schema8.tyre_watch_changes = 1;
  schema8.tyre_watch_step = 0.021;
  schema8.tyre_watch_step_sigma = 3.2;
  schema8.tyre_watch_suspected = true;
  schema8.pair_fit_applies = true;
  schema8.pair_fit_pairs = 412;
  schema8.pair_fit_rotating_error = 0.125;
  schema8.pair_fit_rotating_error_std = 0.0625;
  schema8.pair_fit_converter_multiplied = true;
  schema8.pair_fit_converter_error = -0.25;
  schema8.pair_fit_converter_error_std = std::numeric_limits<double>::quiet_NaN();
  schema8.pair_fit_shift_kg = 230.5;
  schema8.pair_fit_shift_std_kg = 180.25;
  status.commands_received = 1;
  status.last_command_utime = 1733358000000000;
  status.last_command_result = "accepted: known mass 1650.0 kg (std 8.2 kg) from the next tick";
  ASSERT_TRUE(publisher.publish_status(status));
  drain(lcm);

  ASSERT_EQ(rx.estimates.size(), 1u);
  const vmass::mass_estimate_t& e = rx.estimates[0];
  EXPECT_EQ(e.utime, record.estimate.time_us);
  EXPECT_EQ(e.tick, 3);
  EXPECT_TRUE(e.mass_known);
  EXPECT_EQ(e.mass_kg, record.estimate.mass_kg);
  EXPECT_EQ(e.mass_ci_low_kg, record.estimate.ci_low_kg);
  EXPECT_EQ(e.mass_ci_high_kg, record.estimate.ci_high_kg);
  EXPECT_EQ(e.mass_std_kg, 14.0);
  EXPECT_EQ(e.mu_n, -12.5);
  EXPECT_EQ(e.initial_mass_kg, 1650.0);
  EXPECT_EQ(e.estimator, "bayes");
  EXPECT_EQ(e.status, static_cast<int>(EstimateStatus::kConverging));
  EXPECT_EQ(e.status_name, "converging");
  EXPECT_EQ(e.reason_name, "refining");
  EXPECT_EQ(e.invalid_inputs, static_cast<std::int32_t>(input_bit(Input::kGear)));
  EXPECT_EQ(e.pairs_used, 321);
  EXPECT_EQ(e.longitudinal_accepted, 250);
  EXPECT_EQ(e.longitudinal_rejected, 7);
  EXPECT_EQ(e.lateral_accepted, 71);
  EXPECT_DOUBLE_EQ(e.longitudinal_availability, 0.25);
  EXPECT_DOUBLE_EQ(e.lateral_availability, 0.071);
  for (double v : {e.mass_kg, e.mass_std_kg, e.mass_ci_low_kg, e.mass_ci_high_kg, e.mu_n,
                   e.initial_mass_kg, e.longitudinal_availability, e.lateral_availability}) {
    EXPECT_TRUE(std::isfinite(v));
  }

  ASSERT_EQ(rx.pairs.size(), 2u);
  EXPECT_EQ(rx.pairs[0].block_name, "longitudinal");
  EXPECT_TRUE(rx.pairs[0].accepted);
  EXPECT_EQ(rx.pairs[0].y_n, 850.0);
  EXPECT_EQ(rx.pairs[0].delta_accel_mps2, 0.5);
  EXPECT_EQ(rx.pairs[0].test_ratio, 0.05);
  EXPECT_EQ(rx.pairs[0].rotating_n, 21.0);  // schema 4
  EXPECT_EQ(rx.pairs[0].rotating_mass_kg, 42.0);
  EXPECT_EQ(rx.pairs[0].gear, 3);
  EXPECT_EQ(rx.pairs[0].noise_std_n, 60.0);
  EXPECT_EQ(rx.pairs[1].block_name, "lateral");
  EXPECT_FALSE(rx.pairs[1].accepted);
  EXPECT_EQ(rx.pairs[1].verdict_name, std::string(verdict_name(PairVerdict::kSteering)));
  EXPECT_EQ(rx.pairs[1].predicted_y_n, 0.0);  // NaN replaced
  for (const vmass::pair_t& p : rx.pairs) {
    for (double v : {p.y_n, p.delta_accel_mps2, p.weight, p.predicted_y_n, p.innovation_variance_n2,
                     p.test_ratio}) {
      EXPECT_TRUE(std::isfinite(v));
    }
  }

  ASSERT_EQ(rx.statuses.size(), 1u);
  const vmass::status_t& s = rx.statuses[0];
  EXPECT_EQ(s.state_name, "running");
  EXPECT_EQ(s.version, std::string(kVersion));  // vmass/version.hpp, as --version prints
  EXPECT_EQ(s.source, "samples:drive.csv");
  EXPECT_EQ(s.uptime_s, 12.5);
  EXPECT_EQ(s.mass_kg, record.estimate.mass_kg);
  ASSERT_EQ(s.num_inputs, kInputCount);
  EXPECT_EQ(s.input_name[5], "speed");
  EXPECT_DOUBLE_EQ(s.input_age_s[5], 0.05);
  EXPECT_TRUE(s.input_valid[5]);
  EXPECT_FALSE(s.input_valid[static_cast<int>(Input::kGear)]);
  EXPECT_EQ(s.input_age_s[static_cast<int>(Input::kGear)], -1.0);
  EXPECT_EQ(s.frames_received, 1201);
  EXPECT_EQ(s.frames_malformed, 1);
  EXPECT_EQ(s.ticks, 1250);
  EXPECT_EQ(s.tick_overruns, 2);
  EXPECT_EQ(s.jitter_p99_us, 240.0);
  EXPECT_TRUE(s.state_restored);
  EXPECT_EQ(s.schema_version, 8);
  ASSERT_EQ(s.num_verdicts, static_cast<int>(PairVerdict::kCount));
  EXPECT_EQ(s.verdict_name[0], "accepted");
  const auto steering = static_cast<std::size_t>(PairVerdict::kSteering);
  EXPECT_EQ(s.verdict_name[steering], std::string(verdict_name(PairVerdict::kSteering)));
  EXPECT_EQ(s.longitudinal_verdict_ticks[0], 5);  // the record's longitudinal pair: accepted
  EXPECT_EQ(s.lateral_verdict_ticks[steering], 5);
  EXPECT_EQ(s.lateral_verdict_ticks[0], 0);
  EXPECT_EQ(s.learnt_scale, 1.031);
  EXPECT_EQ(s.learnt_scale_std, 0.012);
  EXPECT_EQ(s.learnt_evidence, 2);
  ASSERT_EQ(s.num_learnt_gears, 3);
  EXPECT_EQ(s.learnt_gear_correction_kg[0], -1250.5);
  EXPECT_EQ(s.learnt_gear_correction_kg[2], 12.0);
  EXPECT_EQ(s.learnt_gear_std_kg[1], 150.5);
  EXPECT_EQ(s.learnt_gear_drives, 6);
  EXPECT_EQ(s.learnt_anchors, 4);
  EXPECT_EQ(s.learnt_tyre_changes, 1);
  EXPECT_EQ(s.learnt_evidence_since_tyres, 1);
  EXPECT_EQ(s.tyre_watch_launches, 7);
  EXPECT_EQ(s.tyre_watch_stops, 5);
  EXPECT_EQ(s.tyre_watch_changes, 1);
  EXPECT_EQ(s.tyre_watch_step, 0.021);
  EXPECT_EQ(s.tyre_watch_step_sigma, 3.2);
  EXPECT_TRUE(s.tyre_watch_suspected);
  EXPECT_TRUE(s.pair_fit_applies);
  EXPECT_EQ(s.pair_fit_pairs, 412);
  EXPECT_EQ(s.pair_fit_rotating_error, 0.125);
  EXPECT_EQ(s.pair_fit_rotating_error_std, 0.0625);
  EXPECT_TRUE(s.pair_fit_converter_multiplied);
  EXPECT_EQ(s.pair_fit_converter_error, -0.25);
  EXPECT_EQ(s.pair_fit_converter_error_std, 0.0);  // never NaN on the wire
  EXPECT_EQ(s.pair_fit_shift_kg, 230.5);
  EXPECT_EQ(s.pair_fit_shift_std_kg, 180.25);
  EXPECT_TRUE(s.known_mass);
  EXPECT_EQ(s.commands_received, 1);
  EXPECT_EQ(s.last_command_utime, 1733358000000000);
  EXPECT_EQ(s.last_command_result.rfind("accepted: known mass 1650.0 kg", 0), 0u);
  for (double v : {s.uptime_s, s.mass_kg, s.tick_rate_hz, s.jitter_p50_us, s.jitter_p99_us,
                   s.jitter_max_us, s.wake_latency_max_us, s.tick_compute_max_us}) {
    EXPECT_TRUE(std::isfinite(v));
  }
}

TEST(LcmRoundTrip, DecimationAndPairsOffByDefault) {
  lcm::LCM lcm("memq://");
  LcmSettings settings;
  settings.estimate_decimation = 4;
  Received rx;
  lcm.subscribe(settings.estimate_channel, &Received::on_estimate, &rx);
  lcm.subscribe(settings.pairs_channel, &Received::on_pair, &rx);
  LcmPublisher publisher(lcm, settings, "rls");
  for (int k = 0; k < 10; ++k) {
    ASSERT_TRUE(publisher.on_tick(make_record(k)));
    drain(lcm);
  }
  ASSERT_EQ(rx.estimates.size(), 3u);  // ticks 0, 4, 8
  EXPECT_EQ(rx.estimates[1].tick, 4);
  EXPECT_EQ(rx.estimates[2].tick, 8);
  EXPECT_TRUE(rx.pairs.empty());
  EXPECT_EQ(publisher.estimates_published(), 3);
}

// The generated Python types decode what C++ encodes (same fingerprint, same fields). They need
// only Python's standard library for that (publishing needs the `lcm` module).
TEST(LcmTypes, PythonDecodesWhatCppEncodes) {
  if (std::system("python3 -c 'import struct' > /dev/null 2>&1") != 0) {
    GTEST_SKIP() << "python3 not found";
  }
  vmass::mass_estimate_t m;
  to_lcm(make_record(7), "bayes", &m);
  std::vector<std::uint8_t> buf(static_cast<std::size_t>(m.getEncodedSize()));
  ASSERT_EQ(m.encode(buf.data(), 0, static_cast<int>(buf.size())), static_cast<int>(buf.size()));
  const std::string bin = "/tmp/vmass_py_" + std::to_string(::getpid()) + ".bin";
  const std::string out = bin + ".txt";
  FILE* f = std::fopen(bin.c_str(), "wb");
  ASSERT_NE(f, nullptr);
  std::fwrite(buf.data(), 1, buf.size(), f);
  std::fclose(f);
  const std::string script =
      "import sys; sys.path.insert(0, '" VMASS_LCMTYPES_PYTHON_DIR
      "'); import vmass; "
      "m = vmass.mass_estimate_t.decode(open('" +
      bin +
      "', 'rb').read()); "
      "print(repr(m.mass_kg), m.tick, m.status_name, m.reason_name, m.estimator, "
      "m.longitudinal_accepted, repr(m.mass_ci_high_kg))";
  ASSERT_EQ(std::system(("python3 -c \"" + script + "\" > " + out).c_str()), 0);
  char line[512] = {};
  f = std::fopen(out.c_str(), "r");
  ASSERT_NE(f, nullptr);
  ASSERT_NE(std::fgets(line, sizeof line, f), nullptr);
  std::fclose(f);
  std::remove(bin.c_str());
  std::remove(out.c_str());
  // 1719.25 and 1746.75 are exact in binary: Python's repr prints them exactly.
  EXPECT_STREQ(line, "1719.25 7 converging refining bayes 250 1746.75\n");
}

// ------------------------------------------------------------------------------ sd_notify

class NotifySocket {
 public:
  NotifySocket() {
    path_ = "/tmp/vmass_notify_" + std::to_string(::getpid()) + "_" + std::to_string(counter_++) +
            ".sock";
    fd_ = ::socket(AF_UNIX, SOCK_DGRAM | SOCK_CLOEXEC, 0);
    sockaddr_un addr{};
    addr.sun_family = AF_UNIX;
    std::snprintf(addr.sun_path, sizeof addr.sun_path, "%s", path_.c_str());
    ::unlink(path_.c_str());
    ok_ = fd_ >= 0 && ::bind(fd_, reinterpret_cast<sockaddr*>(&addr), sizeof addr) == 0;
    timeval tv{5, 0};
    ::setsockopt(fd_, SOL_SOCKET, SO_RCVTIMEO, &tv, sizeof tv);
  }
  ~NotifySocket() {
    if (fd_ >= 0) ::close(fd_);
    ::unlink(path_.c_str());
  }
  bool ok() const { return ok_; }
  const std::string& path() const { return path_; }
  /// Next datagram ("" after the 5 s receive timeout).
  std::string next() {
    char buf[4096];
    const ssize_t n = ::recv(fd_, buf, sizeof buf, 0);
    return n > 0 ? std::string(buf, static_cast<std::size_t>(n)) : std::string();
  }
  /// Datagrams until one contains `what` (or the timeout); all of them, in order.
  std::vector<std::string> until(const std::string& what) {
    std::vector<std::string> got;
    for (;;) {
      std::string m = next();
      if (m.empty()) return got;
      got.push_back(m);
      if (m.find(what) != std::string::npos) return got;
    }
  }
  int fd() const { return fd_; }

 private:
  static inline int counter_ = 0;
  std::string path_;
  int fd_ = -1;
  bool ok_ = false;
};

TEST(SystemdNotifier, SpeaksTheNotifyProtocol) {
  NotifySocket sock;
  ASSERT_TRUE(sock.ok());
  ::setenv("NOTIFY_SOCKET", sock.path().c_str(), 1);
  ::setenv("WATCHDOG_USEC", "2000000", 1);
  ::setenv("WATCHDOG_PID", std::to_string(::getpid()).c_str(), 1);
  SystemdNotifier n;  // sd_notify() reads $NOTIFY_SOCKET at each call: kept until the end
  ASSERT_TRUE(n.enabled());
  EXPECT_EQ(n.watchdog_usec(), 2'000'000u);
  EXPECT_EQ(n.watchdog_ping_interval_usec(), 1'000'000u);

  EXPECT_TRUE(n.ready());
  EXPECT_EQ(sock.next(), "READY=1");
  EXPECT_TRUE(n.status("running: 1712 kg\nconverging"));
  EXPECT_EQ(sock.next(), "STATUS=running: 1712 kg converging");
  EXPECT_FALSE(n.status("running: 1712 kg\nconverging"));  // unchanged: not resent
  EXPECT_TRUE(n.status("running: 1713 kg"));
  EXPECT_EQ(sock.next(), "STATUS=running: 1713 kg");

  EXPECT_TRUE(n.watchdog_due(5'000'000));  // never sent yet
  EXPECT_TRUE(n.watchdog());
  n.watchdog_sent(5'000'000);
  EXPECT_EQ(sock.next(), "WATCHDOG=1");
  EXPECT_FALSE(n.watchdog_due(5'999'999));
  EXPECT_TRUE(n.watchdog_due(6'000'000));
  EXPECT_TRUE(n.stopping());
  EXPECT_EQ(sock.next(), "STOPPING=1");
  EXPECT_EQ(n.notifications_sent(), 5u);
  ::unsetenv("NOTIFY_SOCKET");
  ::unsetenv("WATCHDOG_USEC");
  ::unsetenv("WATCHDOG_PID");
}

TEST(SystemdNotifier, NoSocketNoNotifications) {
  ::unsetenv("NOTIFY_SOCKET");
  SystemdNotifier n;
  EXPECT_FALSE(n.enabled());
  EXPECT_FALSE(n.ready());
  EXPECT_FALSE(n.watchdog_due(1'000'000'000));
}

// The daemon itself under a fake systemd: READY=1 after start-up, STATUS= lines, WATCHDOG=1 while
// the estimator ticks, STOPPING=1 on SIGTERM, exit 0.
/// 30 s of standstill samples at 100 Hz and a config for them (plus `extra` YAML).
bool write_idle_drive(const std::string& csv, const std::string& config, const std::string& extra) {
  FILE* f = std::fopen(csv.c_str(), "w");
  if (f == nullptr) return false;
  std::fprintf(f,
               "time_s,wheel_torque_nm,brake_pressure_pa,accel_x_mps2,accel_y_mps2,"
               "yaw_rate_radps,speed_mps,steering_wheel_angle_rad,"
               "rear_right_deflection_m,gear\n");
  for (int i = 0; i <= 3000; ++i) std::fprintf(f, "%.2f,0,0,0,0,0,0,0,0.01,1\n", i * 0.01);
  std::fclose(f);
  f = std::fopen(config.c_str(), "w");
  if (f == nullptr) return false;
  std::fprintf(f,
               "vehicle:\n  empty_mass_kg: 1500\n  wheelbase_m: 2.7\n"
               "  cg_to_front_axle_m: 1.2\n  wheel_radius_m: 0.31\n"
               "  brake_gain_n_per_pa: 0.0033\n  steering_ratio: 15.5\n"
               "  cornering_stiffness_front_n_per_rad: 150000\n"
               "  cornering_stiffness_rear_n_per_rad: 170000\n"
               "suspension:\n  stiffness_n_per_m: 30000\n%s",
               extra.c_str());
  std::fclose(f);
  return true;
}

TEST(SystemdNotifier, DaemonNotifiesReadyWatchdogStatusAndStopping) {
  NotifySocket sock;
  ASSERT_TRUE(sock.ok());
  const std::string dir = "/tmp/vmass_notify_daemon_" + std::to_string(::getpid());
  ASSERT_EQ(std::system(("mkdir -p " + dir).c_str()), 0);
  // 30 s of samples at real speed: it keeps running until the SIGTERM below.
  const std::string csv = dir + "/samples.csv";
  const std::string config = dir + "/vmassd.yaml";
  ASSERT_TRUE(write_idle_drive(csv, config, ""));
  // WATCHDOG_PID unset: sd_watchdog_enabled() accepts the watchdog for any process.
  const std::string command = "NOTIFY_SOCKET=" + sock.path() +
                              " WATCHDOG_USEC=400000 " VMASSD_BIN " --config " + config +
                              " --samples " + csv +
                              " --lcm-url memq:// --no-restore"
                              " > " +
                              dir + "/log.txt 2>&1 & echo $! > " + dir + "/pid";
  ASSERT_EQ(std::system(command.c_str()), 0);

  const std::vector<std::string> start = sock.until("READY=1");
  ASSERT_FALSE(start.empty());
  EXPECT_NE(start.back().find("READY=1"), std::string::npos);
  EXPECT_NE(start.back().find("STATUS="), std::string::npos);  // READY=1 carries a STATUS=
  // Pings at half of 400 ms while ticking; and STATUS= lines once a second.
  int watchdogs = 0, statuses = 0;
  for (int i = 0; i < 40 && (watchdogs < 3 || statuses < 1); ++i) {
    const std::string m = sock.next();
    ASSERT_FALSE(m.empty()) << "daemon stopped notifying";
    watchdogs += m == "WATCHDOG=1";
    statuses += m.rfind("STATUS=", 0) == 0;
  }
  EXPECT_GE(watchdogs, 3);
  EXPECT_GE(statuses, 1);

  ASSERT_EQ(std::system(("kill -TERM $(cat " + dir + "/pid)").c_str()), 0);
  const std::vector<std::string> stop = sock.until("STOPPING=1");
  ASSERT_FALSE(stop.empty());
  EXPECT_NE(stop.back().find("STOPPING=1"), std::string::npos);
  // Exit status 0 (wait for the process to go, then read it from the log's last line).
  ASSERT_EQ(std::system(("for i in $(seq 50); do kill -0 $(cat " + dir +
                         "/pid) 2>/dev/null || exit 0; sleep 0.1; done; exit 1")
                            .c_str()),
            0)
      << "vmassd did not stop within 5 s of SIGTERM";
  EXPECT_EQ(std::system(("grep -q 'stopped:' " + dir + "/log.txt").c_str()), 0);
  std::system(("rm -rf " + dir).c_str());
}

TEST(SystemdNotifier, AStalledEstimatorThreadGetsNoWatchdogPing) {
  NotifySocket sock;
  ASSERT_TRUE(sock.ok());
  timeval tv{0, 100'000};  // 100 ms: the pipe below is drained between datagrams
  ASSERT_EQ(::setsockopt(sock.fd(), SOL_SOCKET, SO_RCVTIMEO, &tv, sizeof tv), 0);
  const std::string dir = "/tmp/vmass_notify_stall_" + std::to_string(::getpid());
  ASSERT_EQ(std::system(("rm -rf " + dir + " && mkdir -p " + dir).c_str()), 0);
  const std::string csv = dir + "/samples.csv";
  const std::string config = dir + "/vmassd.yaml";
  ASSERT_TRUE(write_idle_drive(csv, config, "daemon:\n  publish_queue: 16\n"));
  // LCM writes its log into a pipe nobody reads: once the pipe (64 KiB) and the publish queue
  // are full, the estimator thread of a recording waits to publish (it never drops) and stops
  // ticking; the main loop still runs and sends STATUS= lines.
  const std::string pipe = dir + "/lcm.pipe";
  ASSERT_EQ(::mkfifo(pipe.c_str(), 0600), 0);
  const int reader = ::open(pipe.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  ASSERT_GE(reader, 0);
  const std::string command =
      "NOTIFY_SOCKET=" + sock.path() + " WATCHDOG_USEC=400000 " VMASSD_BIN " --config " + config +
      " --samples " + csv + " --no-restore --state-file " + dir + "/state --lcm-url 'file://" +
      pipe + "?mode=w' > " + dir + "/log.txt 2>&1 & echo $! > " + dir + "/pid";
  ASSERT_EQ(std::system(command.c_str()), 0);
  using Clock = std::chrono::steady_clock;
  auto seconds_since = [](Clock::time_point t) {
    return std::chrono::duration<double>(Clock::now() - t).count();
  };
  // Not reading: the pings stop (the main loop runs on: the pings come back below, and a
  // STATUS= line is sent only when it changes, which it does not while nothing ticks).
  const Clock::time_point t0 = Clock::now();
  Clock::time_point last_ping = t0;
  int pings = 0;
  while (seconds_since(t0) < 15.0 && !(pings >= 3 && seconds_since(last_ping) > 2.0)) {
    if (sock.next() == "WATCHDOG=1") {
      ++pings;
      last_ping = Clock::now();
    }
  }
  EXPECT_GE(pings, 3) << "it ticked before the pipe filled";
  EXPECT_GT(seconds_since(last_ping), 2.0) << "pinged while its estimator thread was stalled";
  // Reading again: the estimator thread ticks and the pings come back.
  char buf[65536];
  int pings_after = 0;
  for (const Clock::time_point t1 = Clock::now(); seconds_since(t1) < 5.0 && pings_after < 3;) {
    while (::read(reader, buf, sizeof buf) > 0) {
    }
    pings_after += sock.next() == "WATCHDOG=1";
  }
  EXPECT_GE(pings_after, 3) << "no pings once the estimator thread ran again";
  ASSERT_EQ(std::system(("kill -TERM $(cat " + dir + "/pid)").c_str()), 0);
  for (const Clock::time_point t2 = Clock::now(); seconds_since(t2) < 5.0;) {
    while (::read(reader, buf, sizeof buf) > 0) {
    }
    if (sock.next().find("STOPPING=1") != std::string::npos) break;
  }
  ASSERT_EQ(std::system(("for i in $(seq 50); do kill -0 $(cat " + dir +
                         "/pid) 2>/dev/null || exit 0; sleep 0.1; done; exit 1")
                            .c_str()),
            0)
      << "vmassd did not stop within 5 s of SIGTERM";
  ::close(reader);
  EXPECT_EQ(std::system(("grep -q 'stopped:' " + dir + "/log.txt").c_str()), 0);
  if (!::testing::Test::HasFailure()) std::system(("rm -rf " + dir).c_str());
}

}  // namespace
}  // namespace vmass::service

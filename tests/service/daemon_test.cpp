// vmassd as a process: offline identity with replay (samples CSV, and the simulated drive's CAN
// log through the signal table), SIGKILL and resume, LCM across processes in a private network
// namespace.
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>
#include <lcm/lcm-cpp.hpp>
#include <vmass/mass_estimate_t.hpp>
#include <vmass/status_t.hpp>

#include "daemon_process.hpp"
#include "test_drive.hpp"
#include "vmass/can/candump.hpp"
#include "vmass/config/config.hpp"
#include "vmass/csv/estimate_csv.hpp"
#include "vmass/csv/samples_csv.hpp"
#include "vmass/runtime/recording.hpp"
#include "vmass/runtime/tick_driver.hpp"
#include "vmass/service/state_store.hpp"
#include "vmass/signals/signal_mapping.hpp"
#include "vmass/signals/signal_table.hpp"
#include "vmass/sim/sensor_model.hpp"

namespace vmass {
namespace {

namespace fs = std::filesystem;

using DaemonTest = test::DaemonProcessTest;

struct LoggedRun {
  std::vector<vmass::mass_estimate_t> estimates;
  std::vector<vmass::status_t> statuses;
};

LoggedRun read_lcm_log(const std::string& file) {
  LoggedRun out;
  lcm::LogFile log(file, "r");
  if (!log.good()) return out;
  while (const lcm::LogEvent* ev = log.readNextEvent()) {
    if (ev->channel == "VMASS_ESTIMATE") {
      vmass::mass_estimate_t m;
      if (m.decode(ev->data, 0, ev->datalen) == ev->datalen) out.estimates.push_back(m);
    } else if (ev->channel == "VMASS_STATUS") {
      vmass::status_t m;
      if (m.decode(ev->data, 0, ev->datalen) == ev->datalen) out.statuses.push_back(m);
    }
  }
  return out;
}

/// The Estimate a mass_estimate_t carries (for EstimateCsvWriter::row).
Estimate from_lcm(const vmass::mass_estimate_t& m) {
  Estimate e;
  e.time_us = m.utime;
  e.mass_known = m.mass_known;
  e.mass_kg = m.mass_kg;
  e.mass_std_kg = m.mass_std_kg;
  e.ci_low_kg = m.mass_ci_low_kg;
  e.ci_high_kg = m.mass_ci_high_kg;
  e.mu_n = m.mu_n;
  e.initial_mass_kg = m.initial_mass_kg;
  e.pairs_used = static_cast<long>(m.pairs_used);
  e.status = static_cast<EstimateStatus>(m.status);
  e.reason = static_cast<StatusReason>(m.reason);
  e.invalid_inputs = static_cast<InputMask>(m.invalid_inputs);
  e.blocks[0].ticks = static_cast<long>(m.longitudinal_ticks);
  e.blocks[0].accepted = static_cast<long>(m.longitudinal_accepted);
  e.blocks[0].rejected_innovation = static_cast<long>(m.longitudinal_rejected);
  e.blocks[1].ticks = static_cast<long>(m.lateral_ticks);
  e.blocks[1].accepted = static_cast<long>(m.lateral_accepted);
  e.blocks[1].rejected_innovation = static_cast<long>(m.lateral_rejected);
  return e;
}

/// Row-for-row comparison of a vmass-replay --out CSV with the daemon's published estimates.
void expect_csv_matches(const std::string& csv, const LoggedRun& daemon) {
  std::ifstream in(csv);
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, EstimateCsvWriter::header());
  std::size_t row = 0;
  while (std::getline(in, line)) {
    ASSERT_LT(row, daemon.estimates.size());
    ASSERT_EQ(line, EstimateCsvWriter::row(from_lcm(daemon.estimates[row]))) << "row " << row;
    ++row;
  }
  EXPECT_EQ(row, daemon.estimates.size());
}

/// The bitwise comparison of the daemon's estimates with an offline run.
void expect_bit_identical(const LoggedRun& daemon, const std::vector<Estimate>& offline) {
  ASSERT_EQ(daemon.estimates.size(), offline.size());
  for (std::size_t i = 0; i < offline.size(); ++i) {
    const vmass::mass_estimate_t& d = daemon.estimates[i];
    const Estimate& o = offline[i];
    ASSERT_EQ(d.utime, o.time_us) << i;
    ASSERT_EQ(d.tick, static_cast<std::int64_t>(i));
    ASSERT_EQ(d.mass_kg, o.mass_kg) << i;  // bitwise: same doubles
    ASSERT_EQ(d.mass_ci_low_kg, o.ci_low_kg) << i;
    ASSERT_EQ(d.mass_ci_high_kg, o.ci_high_kg) << i;
    ASSERT_EQ(d.mass_std_kg, o.mass_std_kg) << i;
    ASSERT_EQ(d.mu_n, o.mu_n) << i;
    ASSERT_EQ(d.pairs_used, o.pairs_used) << i;
    ASSERT_EQ(d.status, static_cast<int>(o.status)) << i;
    ASSERT_EQ(d.reason, static_cast<int>(o.reason)) << i;
    ASSERT_EQ(d.invalid_inputs, static_cast<std::int32_t>(o.invalid_inputs)) << i;
    ASSERT_EQ(d.longitudinal_accepted, o.blocks[0].accepted) << i;
    ASSERT_EQ(d.lateral_accepted, o.blocks[1].accepted) << i;
  }
}

// `vmassd --samples CSV --speed max` ticks in log time and must give exactly what offline replay
// gives: checked bit for bit against the offline loop (runtime::TickDriver + Pipeline, as
// vmass-replay runs it: what the daemon's threads, rings and LCM must not change) and, row for
// row, against the vmass-replay binary's CSV.
TEST_F(DaemonTest, MaxSpeedReplayIsBitIdenticalToOfflineReplay) {
  for (const std::string type : {"bayes", "rls"}) {
    SCOPED_TRACE(type);
    const std::string config = write_config("", type);
    const std::string log = path("out_" + type + ".lcm");
    ASSERT_EQ(run(std::string(VMASSD_BIN) + " --config " + config + " --samples " + csv_ +
                  " --speed max --no-restore --lcm-url 'file://" + log + "?mode=w' 2> " +
                  path("vmassd.log")),
              0)
        << read("vmassd.log");
    const LoggedRun daemon = read_lcm_log(log);

    // The offline loop.
    ConfigLoad c = load_config(config);
    ASSERT_TRUE(c.ok()) << c.error;
    const PipelineParams& params = c.config->pipeline;
    const double rate_hz = params.estimator.differencing.tick_rate_hz;
    Pipeline pipeline(params);
    std::vector<Estimate> offline;
    std::string error;
    auto source =
        runtime::SamplesCsvSource::open(csv_, runtime::default_samples_timeout_s(rate_hz), &error);
    ASSERT_TRUE(source) << error;
    runtime::UnpacedClock clock;
    runtime::TickDriver(*source, rate_hz).run(clock, [&](std::int64_t, TimeUs t) {
      pipeline.step(source->sample_at(t));
      offline.push_back(pipeline.estimate());
    });
    ASSERT_GT(offline.back().pairs_used, 50);
    expect_bit_identical(daemon, offline);
    // The final status closes the run (state stopping) and counts every row.
    ASSERT_FALSE(daemon.statuses.empty());
    const vmass::status_t& last = daemon.statuses.back();
    EXPECT_EQ(last.state_name, "stopping");
    EXPECT_EQ(last.ticks, static_cast<std::int64_t>(offline.size()));
    EXPECT_EQ(last.frames_decoded, static_cast<std::int64_t>(test::make_drive({}).size()));
    EXPECT_EQ(last.publish_queue_drops, 0);

    const std::string replay_csv = path("replay_" + type + ".csv");
    ASSERT_EQ(run(std::string(VMASS_REPLAY_BIN) + " --config " + config + " --samples " + csv_ +
                  " --out " + replay_csv + " > /dev/null"),
              0);
    expect_csv_matches(replay_csv, daemon);
  }
}

// The simulated paper_exp2 drive on CAN (vmass-sim's drive.log, vehicle.dbc and the can:
// mapping of its config.yaml): `vmassd --replay drive.log --speed max` decodes the frames through
// the SignalTable and must give exactly what an offline SignalTable loop gives (bitwise, every
// tick), and row for row what `vmass-replay --log` writes; so must a paced replay (--speed 40,
// all threads); and a good estimate.
TEST_F(DaemonTest, CanLogReplayIsBitIdenticalToVmassReplayLog) {
  const std::string sim = path("sim");
  ASSERT_EQ(run(std::string(VMASS_SIM_BIN) + " --scenario paper_exp2 --seed 3 --out " + sim +
                " > /dev/null"),
            0);
  const std::string log = sim + "/drive.log";
  std::ifstream sim_config_in(sim + "/config.yaml");
  std::stringstream sim_config;
  sim_config << sim_config_in.rdbuf();
  for (const std::string type : {"bayes", "rls"}) {
    SCOPED_TRACE(type);
    // The simulator's config, with the estimator type set (the line "  type: bayes").
    std::string text = sim_config.str();
    const std::size_t at = text.find("  type: bayes");
    ASSERT_NE(at, std::string::npos);
    text.replace(at, 13, "  type: " + type);
    const std::string config = sim + "/config_" + type + ".yaml";  // beside vehicle.dbc
    ASSERT_TRUE(test::write_text(config, text));

    const std::string lcm_log = path("out_" + type + ".lcm");
    ASSERT_EQ(run(std::string(VMASSD_BIN) + " --config " + config + " --replay " + log +
                  " --speed max --no-restore --lcm-url 'file://" + lcm_log + "?mode=w' 2> " +
                  path("vmassd.log")),
              0)
        << read("vmassd.log");
    const LoggedRun daemon = read_lcm_log(lcm_log);

    // Offline: candump reader -> SignalTable -> ticks at T_0 + k / rate after every frame
    // stamped at or before them -> Pipeline (docs: vmass-replay --log).
    ConfigLoad c = load_config(config);
    ASSERT_TRUE(c.ok()) << c.error;
    signals::CanInputsLoad can = signals::load_can_inputs(*c.config);
    ASSERT_TRUE(can.ok()) << can.error;
    signals::SignalTable table(can.inputs->decoder, can.inputs->mapping);
    Pipeline pipeline(c.config->pipeline);
    std::vector<Estimate> offline;
    std::ifstream in(log);
    can::CandumpReader reader(in, log);
    can::CandumpRecord record;
    const double rate_hz = c.config->pipeline.estimator.differencing.tick_rate_hz;
    TimeUs t0 = 0, last = 0;
    std::int64_t k = 0, frames = 0;
    auto tick_time = [&](std::int64_t i) {
      return t0 + static_cast<TimeUs>(std::llround(static_cast<double>(i) * 1e6 / rate_hz));
    };
    TimeUs ages_us[kInputCount] = {};  // at the latest tick
    auto tick = [&] {
      const TimeUs t = tick_time(k++);
      pipeline.step(table.sample_at(t));
      offline.push_back(pipeline.estimate());
      for (int i = 0; i < kInputCount; ++i) ages_us[i] = table.age_us(static_cast<Input>(i), t);
    };
    while (reader.next(&record)) {
      if (frames++ == 0) t0 = record.frame.time_us;
      while (tick_time(k) < record.frame.time_us) tick();
      table.on_frame(record.frame, record.frame.time_us);
      last = std::max(last, record.frame.time_us);
    }
    while (tick_time(k) <= last) tick();
    ASSERT_GT(offline.size(), 19'000u);  // 200 s at 100 Hz
    ASSERT_GT(offline.back().pairs_used, 500);
    expect_bit_identical(daemon, offline);

    // Counters and per-input state in the final status come from the table.
    ASSERT_FALSE(daemon.statuses.empty());
    const vmass::status_t& st = daemon.statuses.back();
    EXPECT_EQ(st.state_name, "stopping");
    EXPECT_EQ(st.ticks, static_cast<std::int64_t>(offline.size()));
    EXPECT_EQ(st.frames_received, frames);
    EXPECT_EQ(st.frames_decoded, static_cast<std::int64_t>(table.counters().decoded));
    EXPECT_EQ(st.frames_unknown, 0);
    EXPECT_EQ(st.frames_malformed, 0);
    EXPECT_EQ(st.publish_queue_drops, 0);
    ASSERT_EQ(st.num_inputs, kInputCount);
    for (int i = 0; i < kInputCount; ++i) {
      const auto input = static_cast<Input>(i);
      EXPECT_EQ(st.input_age_s[i], ages_us[i] < 0 ? -1.0 : to_seconds(ages_us[i]))
          << input_name(input);
      // Every input the simulated bus carries is mapped and fresh; the stand-ins are not mapped.
      EXPECT_EQ(st.input_valid[i], (sim::kSensorModelInputs & input_bit(input)) != 0)
          << input_name(input);
    }

    // A good estimate of the simulated 1659 kg car (paper Table V: errors of a few %).
    EXPECT_NEAR(offline.back().mass_kg, 1659.0, 0.03 * 1659.0);

    // Paced by the log (receive thread -> SPSC ring -> estimator thread on its clock) at 40x,
    // and at 1000x, where the estimator falls behind and the ring fills up: the ticks wait for
    // a lagging receive thread (draining meanwhile), so the estimates are the same, bit for bit.
    if (type == "bayes") {
      for (const std::string speed : {"40", "1000"}) {
        SCOPED_TRACE("speed " + speed);
        const std::string paced_log = path("paced" + speed + ".lcm");
        ASSERT_EQ(run(std::string(VMASSD_BIN) + " --config " + config + " --replay " + log +
                      " --speed " + speed + " --no-restore --lcm-url 'file://" + paced_log +
                      "?mode=w' 2> " + path("paced.log")),
                  0)
            << read("paced.log");
        const LoggedRun paced = read_lcm_log(paced_log);
        ASSERT_FALSE(paced.statuses.empty());
        EXPECT_EQ(paced.statuses.back().publish_queue_drops, 0);
        EXPECT_EQ(paced.statuses.back().ticks_skipped, 0);
        expect_bit_identical(paced, offline);
        EXPECT_NE(read("paced.log").find(" 0 input records late"), std::string::npos)
            << read("paced.log");
      }
    }

    const std::string replay_csv = path("replay_" + type + ".csv");
    ASSERT_EQ(run(std::string(VMASS_REPLAY_BIN) + " --config " + config + " --log " + log +
                  " --out " + replay_csv + " > /dev/null 2>&1"),
              0);
    expect_csv_matches(replay_csv, daemon);
  }
}

// SIGKILL in the middle of a drive, then a restart: the state saved before the kill is intact
// (atomic writes) and the new run starts from it instead of from the static prior.
TEST_F(DaemonTest, SigkillMidDriveThenRestartResumesFromSavedState) {
  // input_timeout_s 0.5 s of log time = 50 ms of wall time at 10x: room for a loaded machine.
  const std::string config =
      write_config("daemon:\n  persist_interval_s: 0.2\n  input_timeout_s: 0.5\n");
  const std::string state = path("vmassd.state");
  // 60 s drive at 10x: killed after ~3.5 s wall (~35 s of log time, in the middle of the events).
  start(std::string(VMASSD_BIN) + " --config " + config + " --samples " + csv_ +
            " --speed 10 --lcm-url memq:// --state-file " + state,
        "first");
  sleep_s(3.5);
  ASSERT_EQ(run("kill -KILL $(cat " + path("first.pid") + ")"), 0);
  EXPECT_EQ(wait_rc("first", 5.0), 137) << read("first.log");  // 128 + SIGKILL

  ConfigLoad c = load_config(config);
  ASSERT_TRUE(c.ok());
  const service::StateLoad saved =
      service::load_state_file(state, service::state_fingerprint(c.config->pipeline));
  ASSERT_EQ(saved.status, service::StateLoadStatus::kLoaded) << saved.error;
  EXPECT_FALSE(fs::exists(state + ".tmp") && fs::file_size(state + ".tmp") == 0);
  const long saved_pairs = saved.state.snapshot.pairs_used;
  ASSERT_GT(saved_pairs, 0) << "killed before any event was used; log:\n" << read("first.log");
  EXPECT_LT(saved.state.saved_time_us, 60'000'000);  // mid-drive

  // Restarted within the drive (the rest of it, from just after the saved tick, as a systemd
  // restart sees it): no load can have changed, and the first estimate continues the saved
  // belief with its pairs.
  std::vector<Sample> rest;
  for (const Sample& s : test::make_drive(test::DriveSpec{})) {
    if (s.time_us > saved.state.saved_time_us) rest.push_back(s);
  }
  const std::string rest_csv = path("rest.csv");
  ASSERT_TRUE(test::write_samples_csv(rest_csv, rest));
  const std::string log = path("second.lcm");
  ASSERT_EQ(run(std::string(VMASSD_BIN) + " --config " + config + " --samples " + rest_csv +
                " --speed max --lcm-url 'file://" + log + "?mode=w' --state-file " + state +
                " 2> " + path("second.log")),
            0)
      << read("second.log");
  const LoggedRun second = read_lcm_log(log);
  ASSERT_GT(second.estimates.size(), 400u);
  const vmass::mass_estimate_t& first_estimate = second.estimates.front();
  EXPECT_TRUE(first_estimate.mass_known);
  EXPECT_EQ(first_estimate.pairs_used, saved_pairs);
  EXPECT_EQ(first_estimate.initial_mass_kg, saved.state.snapshot.prior.mass_kg);
  EXPECT_NE(first_estimate.reason_name, "load_unchecked");
  EXPECT_GE(second.estimates[400].pairs_used, saved_pairs);
  ASSERT_FALSE(second.statuses.empty());
  EXPECT_TRUE(second.statuses.back().state_restored);
  EXPECT_NE(read("second.log").find("restored"), std::string::npos);

  // Without the saved state the same drive starts from nothing.
  const std::string fresh = path("fresh.lcm");
  const std::string fresh_state = path("fresh.state");
  ASSERT_EQ(run(std::string(VMASSD_BIN) + " --config " + config + " --samples " + csv_ +
                " --speed max --no-restore --lcm-url 'file://" + fresh + "?mode=w' --state-file " +
                fresh_state + " 2> /dev/null"),
            0);
  const LoggedRun fresh_run = read_lcm_log(fresh);
  ASSERT_FALSE(fresh_run.estimates.empty());
  EXPECT_EQ(fresh_run.estimates.front().pairs_used, 0);
  EXPECT_FALSE(fresh_run.estimates.front().mass_known);
  // The final save flushed the open Bayes batch: every accepted pair is in the saved belief.
  const service::StateLoad final_state =
      service::load_state_file(fresh_state, service::state_fingerprint(c.config->pipeline));
  ASSERT_EQ(final_state.status, service::StateLoadStatus::kLoaded) << final_state.error;
  const vmass::mass_estimate_t& last = fresh_run.estimates.back();
  EXPECT_EQ(final_state.state.snapshot.pairs_used,
            last.longitudinal_accepted + last.lateral_accepted);
}

// A bad config is refused with file:line:key and exit code 2; an unknown CLI combination too.
// A state file damaged on disk (cut short, a byte changed) or believable to its checksum only
// (a mass of -5000 kg): vmassd says why, starts fresh (not restored), exits 0, and its final
// save replaces the file with one that loads.
TEST_F(DaemonTest, DamagedStateFilesAreRefusedWithTheirReasonAndReplaced) {
  const std::string config = write_config("");
  const std::string good = path("good.state");
  ASSERT_EQ(run(std::string(VMASSD_BIN) + " --config " + config + " --samples " + csv_ +
                " --speed max --lcm-url memq:// --state-file " + good + " 2> " + path("good.log")),
            0)
      << read("good.log");
  const ConfigLoad c = load_config(config);
  ASSERT_TRUE(c.ok());
  const std::uint64_t fingerprint = service::state_fingerprint(c.config->pipeline);
  const service::StateLoad saved = service::load_state_file(good, fingerprint);
  ASSERT_EQ(saved.status, service::StateLoadStatus::kLoaded) << saved.error;
  const std::string text = read("good.state");
  std::string garbled = text;
  const std::size_t digit = garbled.find_first_of("123456789", garbled.size() / 2);
  ASSERT_NE(digit, std::string::npos);
  garbled[digit] = garbled[digit] == '9' ? '1' : static_cast<char>(garbled[digit] + 1);
  service::SavedState absurd = saved.state;
  absurd.snapshot.nig_mean[0] = -5000.0;  // the test config's estimator is Bayes
  const std::string absurd_text = service::format_state(absurd);

  struct Case {
    const char* name;
    std::string contents;
    std::string reason;
  };
  const Case cases[] = {
      {"truncated", text.substr(0, text.size() / 2), "no checksum line (truncated file?)"},
      {"garbled", garbled, "checksum mismatch (corrupt file)"},
      {"implausible", absurd_text,
       "saved state not believable (Bayes mass -5000 kg outside the plausible band [1350, 4500] "
       "kg)"},
  };
  for (const Case& k : cases) {
    const std::string state = path(std::string(k.name) + ".state");
    const std::string log = path(std::string(k.name) + ".log");
    const std::string lcm_log = path(std::string(k.name) + ".lcm");
    ASSERT_TRUE(test::write_text(state, k.contents));
    EXPECT_EQ(run(std::string(VMASSD_BIN) + " --config " + config + " --samples " + csv_ +
                  " --speed max --lcm-url 'file://" + lcm_log + "?mode=w' --state-file " + state +
                  " 2> " + log),
              0)
        << k.name << ": " << read(std::string(k.name) + ".log");
    const std::string out = read(std::string(k.name) + ".log");
    EXPECT_NE(out.find(k.reason), std::string::npos) << k.name << ": " << out;
    EXPECT_NE(out.find("starting fresh"), std::string::npos) << k.name << ": " << out;
    const LoggedRun run_log = read_lcm_log(lcm_log);
    ASSERT_FALSE(run_log.statuses.empty()) << k.name;
    EXPECT_FALSE(run_log.statuses.back().state_restored) << k.name;
    const service::StateLoad after = service::load_state_file(state, fingerprint);
    EXPECT_EQ(after.status, service::StateLoadStatus::kLoaded) << k.name << ": " << after.error;
    EXPECT_GT(after.state.snapshot.nig_mean[0], 1000.0) << k.name;
  }
}

TEST_F(DaemonTest, RefusesToStartOnConfigErrors) {
  const std::string config = write_config("lcm:\n  estimate_chanel: X\n");
  EXPECT_EQ(run(std::string(VMASSD_BIN) + " --config " + config + " --samples " + csv_ +
                " --lcm-url memq:// 2> " + path("err.txt")),
            2);
  EXPECT_NE(read("err.txt").find("vmassd.yaml:19: lcm.estimate_chanel: unknown key"),
            std::string::npos)
      << read("err.txt");
  const std::string good = write_config("");
  EXPECT_EQ(run(std::string(VMASSD_BIN) + " --config " + good + " --samples " + csv_ +
                " --speed fast --lcm-url memq:// 2> /dev/null"),
            2);
  EXPECT_NE(run(std::string(VMASSD_BIN) + " --config " + good + " --samples " + csv_ +
                " --can can0 2> /dev/null"),
            0);
}

// Two processes, UDP multicast, inside a private network namespace (nothing leaves the machine):
// vmassd replays at real speed, vmass-monitor measures what arrives.
TEST_F(DaemonTest, CrossProcessMulticastMeetsTheRateInAPrivateNetns) {
  if (run("unshare -n true 2> /dev/null") != 0) {
    GTEST_SKIP() << "unshare -n not permitted here (needs root or user namespaces)";
  }
  const std::string config = write_config("lcm:\n  url: \"udpm://239.255.76.67:7667?ttl=0\"\n");
  const std::string script = path("netns.sh");
  ASSERT_TRUE(test::write_text(script,
                               "set -e\n"
                               "ip link set lo up\n"
                               "ip route add 224.0.0.0/4 dev lo\n" +
                                   std::string(VMASSD_BIN) + " --config " + config + " --samples " +
                                   csv_ + " --no-restore > " + path("daemon.log") +
                                   " 2>&1 &\n"
                                   "daemon=$!\n"
                                   "sleep 1\n" VMASS_MONITOR_BIN " --config " +
                                   config + " --rates 6 > " + path("rates.txt") +
                                   "\n"
                                   "monitor=$?\n"
                                   "kill -TERM $daemon\n"
                                   "wait $daemon\n"
                                   "exit $monitor\n"));
  ASSERT_EQ(run("unshare -n sh " + script), 0) << read("rates.txt") << read("daemon.log");
  const std::string rates = read("rates.txt");
  double estimate_hz = 0.0, status_hz = 0.0;
  long estimates = 0, statuses = 0, bad_e = -1, bad_s = -1;
  ASSERT_EQ(std::sscanf(rates.c_str(),
                        "VMASS_ESTIMATE messages=%ld rate_hz=%lf nonfinite_fields=%ld\n"
                        "VMASS_STATUS messages=%ld rate_hz=%lf nonfinite_fields=%ld",
                        &estimates, &estimate_hz, &bad_e, &statuses, &status_hz, &bad_s),
            6)
      << rates;
  EXPECT_NEAR(estimate_hz, 100.0, 5.0) << rates;  // within 5 %
  EXPECT_NEAR(status_hz, 1.0, 0.05) << rates;
  EXPECT_GE(estimates, 500);
  EXPECT_GE(statuses, 5);
  EXPECT_EQ(bad_e, 0);
  EXPECT_EQ(bad_s, 0);
  EXPECT_NE(read("daemon.log").find("stopped:"), std::string::npos);
}

}  // namespace
}  // namespace vmass

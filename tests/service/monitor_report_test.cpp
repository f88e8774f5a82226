// vmass-monitor's report fits an 80-column terminal with everything vmassd publishes at its
// widest (nine inputs, large counters, a long input path), and keeps every item.
#include <gtest/gtest.h>

#include <sstream>
#include <string>

#include "monitor_report.hpp"
#include "vmass/core/sample.hpp"

namespace vmass::monitor {
namespace {

vmass::status_t wide_status() {
  vmass::status_t s{};
  s.state_name = "input_lost";
  s.version = "0.1.0";
  s.source = "replay:/var/lib/vmass/recordings/2026-12-01/truck-26t-heavy-rear-load-drive.log";
  s.detail = "interface can0 is down";
  s.uptime_s = 123456.0;
  s.ticks = 123456789012;
  s.tick_rate_hz = 100.0;
  s.tick_overruns = s.ticks_skipped = s.publish_queue_drops = 1234567;
  s.jitter_p50_us = s.jitter_p99_us = s.jitter_max_us = 1234567.0;
  s.frames_received = s.frames_decoded = s.frames_unknown = s.frames_malformed = 98765432109;
  s.frames_dropped = s.bus_errors = s.source_reopens = 98765432109;
  s.num_inputs = kInputCount;
  for (int i = 0; i < kInputCount; ++i) {
    s.input_name.push_back(std::string(input_name(static_cast<Input>(i))));
    s.input_age_s.push_back(i == 3 ? -1.0 : 12345.678);
    s.input_valid.push_back(i % 2 == 0);
  }
  s.tyre_watch_launches = s.tyre_watch_stops = s.tyre_watch_changes = 123456789;
  s.tyre_watch_step = -0.1234;
  s.tyre_watch_step_sigma = 12345.6;
  s.tyre_watch_suspected = true;
  s.pair_fit_applies = s.pair_fit_converter_multiplied = true;
  s.pair_fit_rotating_error = s.pair_fit_converter_error = -12.345;
  s.pair_fit_rotating_error_std = s.pair_fit_converter_error_std = 12.345;
  s.pair_fit_shift_kg = -123456.0;
  s.pair_fit_shift_std_kg = 123456.0;
  s.pair_fit_pairs = 123456789;
  return s;
}

vmass::mass_estimate_t wide_estimate() {
  vmass::mass_estimate_t e{};
  e.mass_known = true;
  e.mass_kg = 26123.4;
  e.mass_ci_low_kg = 25123.4;
  e.mass_ci_high_kg = 27123.4;
  e.mass_std_kg = 1234.5;
  e.mu_n = -123456.7;
  e.status_name = "converging";
  e.reason_name = "longitudinal_only";
  e.estimator = "bayes";
  e.initial_mass_kg = 26000.0;
  e.pairs_used = e.longitudinal_accepted = e.longitudinal_rejected = 123456789;
  e.lateral_accepted = e.lateral_rejected = 123456789;
  e.longitudinal_availability = e.lateral_availability = 1.0;
  e.utime = 1700000000123456;
  return e;
}

TEST(MonitorReport, EveryLineFitsEightyColumns) {
  const vmass::mass_estimate_t e = wide_estimate();
  const vmass::status_t s = wide_status();
  const std::string report = monitor_report("udpm://239.255.76.67:7667?ttl=0", 2000.1, 1.0, &e, &s);
  std::istringstream lines(report);
  std::string line;
  int count = 0;
  while (std::getline(lines, line)) {
    ++count;
    EXPECT_LE(line.size(), kReportWidth) << line;
  }
  EXPECT_GE(count, 10);
  for (const char* item : {"26123.4 kg", "95% [25123.4, 27123.4] kg", "lateral 100.0 %",
                           "version 0.1.0", "98765432109 reopens", "speed INVALID", "gear ok",
                           "accel_y never", "interface can0 is down", "jitter p50/p99/max",
                           "2345.6 std, suspected", "converter -1234 +- 1234 %"}) {
    EXPECT_NE(report.find(item), std::string::npos) << item << " missing:\n" << report;
  }
  // The path longer than a line keeps its start and its end.
  EXPECT_NE(report.find("input replay:/var/lib/vmass/"), std::string::npos) << report;
  EXPECT_NE(report.find("...ruck-26t-heavy-rear-load-drive.log"), std::string::npos) << report;
}

TEST(MonitorReport, WrapsUnderTheFirstItem) {
  EXPECT_EQ(wrap_items("frames", {std::string(40, 'a'), std::string(40, 'b')}),
            "frames    " + std::string(40, 'a') + "\n          " + std::string(40, 'b') + "\n");
  EXPECT_EQ(wrap_items("mass", {}), "mass      \n");
  EXPECT_EQ(monitor_report("memq://", 0.0, 0.0, nullptr, nullptr),
            "vmass-monitor memq://   estimates 0.0 Hz   status 0.00 Hz\n"
            "mass      (no estimate received)\ndaemon    (no status received)\n");
}

/// The status's report holds `text`; else the report, to read.
::testing::AssertionResult report_has(const vmass::status_t& s, const std::string& text) {
  const std::string report = monitor_report("memq://", 0.0, 0.0, nullptr, &s);
  if (report.find(text) != std::string::npos) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << "no '" << text << "' in:\n" << report;
}

TEST(MonitorReport, WhatIsLearntAboutTheCar) {
  vmass::status_t s{};
  s.state_name = "running";
  s.learnt_scale = 1.0;
  s.learnt_scale_std = 0.054;
  EXPECT_TRUE(report_has(s, "\nlearnt    scale: datasheet (no known mass yet)\ndaemon    running"));
  // The deflection sensor's standstill readings anchored it: no known mass yet.
  s.learnt_scale = 0.9812;
  s.learnt_scale_std = 0.0231;
  s.learnt_anchors = 3;
  EXPECT_TRUE(report_has(
      s, "\nlearnt    scale 0.981 +- 2.3 % from 3 standstill readings (no known mass yet)\n"));
  s.learnt_scale = 1.0314;
  s.learnt_scale_std = 0.0123;
  s.learnt_evidence = 2;
  EXPECT_TRUE(report_has(s, "\nlearnt    scale 1.031 +- 1.2 % from 2 drives on a known mass\n"));
  s.learnt_evidence = 1;
  s.learnt_changes = 1;
  EXPECT_TRUE(report_has(s,
                         "\nlearnt    scale 1.031 +- 1.2 % from 1 drive on a known mass\n"
                         "          1 change of the car detected"));
  // The gears' rotating masses: the datasheet's until a drive in two gears taught them.
  s.num_learnt_gears = 2;
  s.learnt_gear_correction_kg = {0.0, 0.0};
  s.learnt_gear_std_kg = {1386.0, 693.0};
  EXPECT_TRUE(report_has(s, "rotating masses: datasheet (no drive with two gears yet)"));
  s.learnt_gear_drives = 3;
  s.learnt_gear_correction_kg = {-1250.4, 36.0};
  s.learnt_gear_std_kg = {400.2, 150.0};
  EXPECT_TRUE(report_has(s, "rotating masses from 3 drives:"));
  EXPECT_TRUE(report_has(s, "gear 1 -1250 +- 400 kg   gear 2 +36 +- 150 kg\n"));
}

// New tyres declared (vmass-ctl tyres-changed): under the widened scale, what taught it since.
TEST(MonitorReport, NewTyresSayWhatTaughtTheScaleSince) {
  vmass::status_t s{};
  s.state_name = "running";
  s.learnt_scale = 1.0314;
  s.learnt_scale_std = 0.0231;
  s.learnt_evidence = 1;
  s.learnt_tyre_changes = 1;
  s.learnt_evidence_since_tyres = 0;
  s.learnt_anchors = 2;
  EXPECT_TRUE(report_has(s,
                         "\nlearnt    scale 1.031 +- 2.3 % from 1 drive on a known mass\n"
                         "          new tyres: 0 known masses and 2 standstill readings since\n"));
  s.learnt_tyre_changes = 2;
  s.learnt_evidence_since_tyres = 1;
  s.learnt_anchors = 0;
  EXPECT_TRUE(report_has(s, "\n          new tyres x2: 1 known mass since\n"));
}

// The tyre watch (schema 8): nothing until it holds a launch; then what it holds, the largest
// step it tried and the changes it told.
TEST(MonitorReport, TheTyreWatchSaysWhatItHoldsAndTold) {
  vmass::status_t s{};
  s.state_name = "running";
  EXPECT_EQ(monitor_report("memq://", 0.0, 0.0, nullptr, &s).find("tyres"), std::string::npos);
  s.tyre_watch_launches = 1;
  EXPECT_TRUE(report_has(s, "\ntyres     1 launch and 0 stops since the last change\ndaemon"));
  s.tyre_watch_launches = 12;
  s.tyre_watch_stops = 8;
  s.tyre_watch_step = 0.0183;
  s.tyre_watch_step_sigma = 3.14;
  s.tyre_watch_suspected = true;
  EXPECT_TRUE(report_has(s,
                         "\ntyres     12 launches and 8 stops since the last change\n"
                         "          largest step +1.8 % (3.1 std, suspected)\n"));
  s.tyre_watch_suspected = false;
  s.tyre_watch_changes = 2;
  EXPECT_TRUE(report_has(s, "(3.1 std)   2 changes told\n"));
}

// The drive's pair-term fit (schema 8), only while it applies; the converter only when some
// pair held its multiplication.
TEST(MonitorReport, ThePairTermFitIsShownWhileItApplies) {
  vmass::status_t s{};
  s.state_name = "running";
  s.pair_fit_rotating_error = 0.12;
  EXPECT_EQ(monitor_report("memq://", 0.0, 0.0, nullptr, &s).find("pair fit"), std::string::npos);
  s.pair_fit_applies = true;
  s.pair_fit_rotating_error_std = 0.09;
  s.pair_fit_shift_kg = 231.0;
  s.pair_fit_shift_std_kg = 180.4;
  s.pair_fit_pairs = 412;
  EXPECT_TRUE(
      report_has(s, "\npair fit  rotating masses +12 +- 9 %   mass +231 +- 180 kg   412 pairs\n"));
  s.pair_fit_converter_multiplied = true;
  s.pair_fit_converter_error = -0.05;
  s.pair_fit_converter_error_std = 0.1;
  EXPECT_TRUE(report_has(s,
                         "\npair fit  rotating masses +12 +- 9 %   converter -5 +- 10 %\n"
                         "          mass +231 +- 180 kg   412 pairs\n"));
}

TEST(MonitorReport, ADeclaredMassSaysSo) {
  vmass::mass_estimate_t e{};
  e.mass_known = true;
  e.mass_kg = 1650.0;
  e.mass_ci_low_kg = 1633.8;
  e.mass_ci_high_kg = 1666.2;
  e.mass_std_kg = 8.25;
  EXPECT_EQ(monitor_report("memq://", 0.0, 0.0, &e, nullptr).find("known (declared)"),
            std::string::npos);
  e.known_mass = true;
  EXPECT_NE(monitor_report("memq://", 0.0, 0.0, &e, nullptr)
                .find("\nmass      1650.0 kg   known (declared)   95% [1633.8, 1666.2] kg   "
                      "std 8.2 kg\n          mu 0.0 N\n"),
            std::string::npos)
      << monitor_report("memq://", 0.0, 0.0, &e, nullptr);
}

TEST(MonitorReport, TheLastCommandsAnswerAndItsAge) {
  vmass::status_t s{};
  s.state_name = "running";
  s.last_command_result = "accepted: known mass 1650.0 kg (std 8.2 kg) from the next tick";
  ReportContext context;
  context.now_utime = 1700000012000000;
  // No command yet: no line, whatever the text.
  EXPECT_EQ(monitor_report("memq://", 0.0, 0.0, nullptr, &s, {}, context).find("command"),
            std::string::npos);
  s.last_command_utime = 1700000000000000;  // 12 s before now
  EXPECT_NE(monitor_report("memq://", 0.0, 0.0, nullptr, &s, {}, context)
                .find("\ncommand   accepted: known mass 1650.0 kg (std 8.2 kg) from the next "
                      "tick\n          (12 s ago)\ndaemon"),
            std::string::npos)
      << monitor_report("memq://", 0.0, 0.0, nullptr, &s, {}, context);
  context.now_utime = s.last_command_utime + 3 * 3600 * 1000000LL;
  s.last_command_result = "refused: unknown command '\x1b[2J\nrm' (known_mass, reset_learnt)";
  const std::string report = monitor_report("memq://", 0.0, 0.0, nullptr, &s, {}, context);
  EXPECT_NE(report.find("\ncommand   refused: unknown command '?[2J?rm' (known_mass, "
                        "reset_learnt)\n          (3 h ago)\n"),
            std::string::npos)
      << report;
  EXPECT_EQ(report.find('\x1b'), std::string::npos);  // no escape reaches the terminal
  context.now_utime = 0;                              // no clock: no age
  EXPECT_EQ(monitor_report("memq://", 0.0, 0.0, nullptr, &s, {}, context).find(" ago)"),
            std::string::npos);
}

TEST(MonitorReport, WhyNoPairCameLately) {
  NoPairStretch stretch;
  stretch.span_s = 180.0;
  stretch.verdict_ticks = {{"small_delta_force", 17800}, {"settling", 200}};
  ReportContext context;
  context.no_pair = stretch;
  EXPECT_EQ(monitor_report("memq://", 0.0, 0.0, nullptr, nullptr, {}, context),
            "vmass-monitor memq://   estimates 0.0 Hz   status 0.00 Hz\n"
            "mass      (no estimate received)\n"
            "why not   no longitudinal pair in 180 s: 17,800 ticks small_delta_force,\n"
            "          200 settling\n"
            "daemon    (no status received)\n");
  stretch.verdict_ticks = {{"small_delta_force", 1234567},
                           {"speed", 20000},
                           {"settling", 300},
                           {"gear_change", 40},
                           {"not_clean", 5}};
  stretch.span_s = 12345.6;
  const std::vector<std::string> items = no_pair_items(stretch);
  const std::vector<std::string> expected = {
      "no longitudinal pair in 12346 s:", "1,234,567 ticks small_delta_force,", "20,000 speed,",
      "300 settling,", "45 in 2 other verdicts"};
  EXPECT_EQ(items, expected);
  EXPECT_TRUE(no_pair_items(NoPairStretch{}).empty());
}

TEST(MonitorReport, EveryNewLineFitsEightyColumnsToo) {
  vmass::mass_estimate_t e = wide_estimate();
  e.known_mass = true;
  vmass::status_t s = wide_status();
  s.learnt_scale = 12.3456;
  s.learnt_scale_std = 1.23456;
  s.learnt_evidence = s.learnt_changes = 1234567890;
  s.last_command_utime = 1;
  s.last_command_result = "refused: " + std::string(150, 'x') + " and some words after it";
  ReportContext context;
  context.now_utime = 1700000000000000;
  context.no_pair.span_s = 123456.0;
  context.no_pair.verdict_ticks = {{"longitudinal_accel", 123456789012},
                                   {"small_delta_accel", 123456789012},
                                   {"inputs_invalid", 123456789012},
                                   {"awaiting_lag", 1}};
  const std::string report =
      monitor_report("udpm://239.255.76.67:7667?ttl=0", 2000.1, 1.0, &e, &s, {}, context);
  std::istringstream lines(report);
  std::string line;
  while (std::getline(lines, line)) EXPECT_LE(line.size(), kReportWidth) << line;
  for (const char* item : {"known (declared)", "scale 12.346 +- 123.5 % from 1234567890 drives",
                           "123,456,789,012 ticks longitudinal_accel,", "1 in 1 other verdicts",
                           "and some words after it", "(472222 h ago)", "1234567890 changes"}) {
    EXPECT_NE(report.find(item), std::string::npos) << item << " missing:\n" << report;
  }
}

}  // namespace
}  // namespace vmass::monitor

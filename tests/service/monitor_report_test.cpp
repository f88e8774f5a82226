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
                           "accel_y never", "interface can0 is down", "jitter p50/p99/max"}) {
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

}  // namespace
}  // namespace vmass::monitor

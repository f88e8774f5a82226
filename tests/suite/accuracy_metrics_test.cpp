// AccuracyMetrics against answers worked out by hand on small synthetic tracks.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "vmass/scoring/accuracy_metrics.hpp"

namespace vmass::scoring {
namespace {

TimeUs tick_time(std::size_t k) { return static_cast<TimeUs>(k) * 100000; }

// 100 s at 10 Hz; the car starts driving at t = 5 s; the true mass is 1000 kg, 1200 kg from
// t = 50 s (a load change).
Truth track() {
  std::vector<TimeUs> times;
  std::vector<double> masses, speeds;
  for (std::size_t k = 0; k <= 1000; ++k) {
    times.push_back(tick_time(k));
    masses.push_back(k < 500 ? 1000.0 : 1200.0);
    speeds.push_back(k < 50 ? 0.0 : 10.0);
  }
  return Truth(std::move(times), std::move(masses), std::move(speeds));
}

TEST(AccuracyMetrics, ErrorsCheckpointsAndToleranceTimes) {
  const Truth t = track();
  EXPECT_EQ(t.drive_start_us(), 5000000);
  AccuracyMetrics m(t);
  for (std::size_t k = 0; k < t.size(); ++k) {
    const double time_s = static_cast<double>(k) / 10.0;
    EstimatePoint p;
    p.time_us = tick_time(k);
    p.has_mass = time_s >= 2.0;
    // 10 % high until 30 s, then 1.5 % high, and after the load change exactly right.
    const double truth = t.mass_at(p.time_us);
    p.mass_kg = truth * (time_s < 30.0 ? 1.10 : (time_s < 50.0 ? 1.015 : 1.0));
    p.has_interval = true;
    p.ci_low_kg = p.mass_kg - 20.0;
    p.ci_high_kg = p.mass_kg + 20.0;
    p.converged = time_s >= 40.0;
    m.add(p);
  }
  const AccuracyResult r = m.result();
  EXPECT_EQ(r.ticks, 1001);
  EXPECT_TRUE(r.has_estimate);
  EXPECT_NEAR(r.final_error_pct, 0.0, 1e-12);
  EXPECT_NEAR(r.true_final_mass_kg, 1200.0, 1e-12);
  EXPECT_NEAR(r.error_at_pct[0], 10.0, 1e-9);  // 25 s: still 10 % high
  EXPECT_NEAR(r.error_at_pct[1], 0.0, 1e-9);   // 65 s
  // Within 5 % from 30 s (25 s after the start), within 1 % from 50 s (45 s after).
  EXPECT_NEAR(r.time_within_since_drive_start_s[0], 24.9, 1e-9);
  EXPECT_NEAR(r.time_within_since_drive_start_s[1], 24.9, 1e-9);
  EXPECT_NEAR(r.time_within_since_drive_start_s[2], 44.9, 1e-9);
  EXPECT_EQ(r.covered_at_checkpoint[0], 0);  // +10 % with +-20 kg
  EXPECT_EQ(r.covered_at_checkpoint[1], 1);
  EXPECT_EQ(r.covered_at_end, 1);
  EXPECT_NEAR(r.halfwidth_end_pct, 100.0 * 20.0 / 1200.0, 1e-9);
  // Converged from 40 s; 1.5 % of 1000 kg is inside the +-20 kg interval: always covered.
  EXPECT_NEAR(r.converged_outside_fraction, 0.0, 1e-12);
  EXPECT_NEAR(r.rms_last_half_pct, 0.0, 1e-12);
}

TEST(AccuracyMetrics, NoEstimateCountsAsOutsideAndNeverWithin) {
  const Truth t = track();
  AccuracyMetrics m(t);
  for (std::size_t k = 0; k < t.size(); ++k) {
    EstimatePoint p;
    p.time_us = tick_time(k);
    m.add(p);
  }
  const AccuracyResult r = m.result();
  EXPECT_FALSE(r.has_estimate);
  EXPECT_TRUE(std::isnan(r.final_error_pct));
  EXPECT_TRUE(std::isnan(r.time_within_since_drive_start_s[0]));
  EXPECT_EQ(r.covered_at_end, -1);
  EXPECT_TRUE(std::isnan(r.rms_last_half_pct));
  EXPECT_TRUE(std::isnan(r.converged_outside_fraction));
}

TEST(AccuracyMetrics, ConvergedThenOutsideIsTheShareOfLaterTicks) {
  const Truth t = track();
  AccuracyMetrics m(t);
  for (std::size_t k = 0; k < t.size(); ++k) {
    EstimatePoint p;
    p.time_us = tick_time(k);
    p.has_mass = p.has_interval = true;
    p.mass_kg = 1000.0;  // wrong after the load change at 50 s
    p.ci_low_kg = 990.0;
    p.ci_high_kg = 1010.0;
    p.converged = k >= 250;  // from 25 s
    m.add(p);
  }
  const AccuracyResult r = m.result();
  // From 25 s to 100 s: 751 ticks, of which 50..100 s (501 ticks) outside.
  EXPECT_NEAR(r.converged_outside_fraction, 501.0 / 751.0, 1e-12);
  EXPECT_NEAR(r.final_error_pct, 100.0 * (1000.0 - 1200.0) / 1200.0, 1e-9);
}

}  // namespace
}  // namespace vmass::scoring

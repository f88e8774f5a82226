// PaperLpBaseline: exact on exact data, within the figures issue 8 reports on a drive like the
// paper's Experiment 1 with production sensor noise, batches, holes.
#include "vmass/baselines/paper_lp_baseline.hpp"

#include <cmath>

#include <gtest/gtest.h>

#include "drive_cases.hpp"
#include "drive_checks.hpp"
#include "exact_streams.hpp"

namespace vmass::baselines {
namespace {

using namespace testing;

TEST(PaperLpBaseline, ExactDataGiveTheMassWithAnIntervalAroundIt) {
  PaperLpBaseline b(exact_car(1500.0), 100.0);
  const auto samples = exact_force_stream(exact_car(1500.0), 2000.0, -300.0, 0.0, 60.0);
  bool published_early = false;
  for (const auto& s : samples) {
    b.step(s);
    // Nothing is published before the first batch of 100 pairs completes.
    if (b.regression().batches() == 0 && b.estimate().has_mass) published_early = true;
  }
  EXPECT_FALSE(published_early);
  const BaselineEstimate e = b.estimate();
  ASSERT_TRUE(e.has_mass);
  EXPECT_NEAR(e.mass_kg, 2000.0, 0.001 * 2000.0);
  ASSERT_TRUE(e.has_interval);
  EXPECT_LT(e.ci_low_kg, e.mass_kg);
  EXPECT_GT(e.ci_high_kg, e.mass_kg);
  EXPECT_LT(e.ci_high_kg - e.ci_low_kg, 0.01 * 2000.0);  // noiseless: a narrow interval
  EXPECT_EQ(e.updates % 100, 0);                         // whole batches only
}

TEST(PaperLpBaseline, LikeExperiment1WithProductionSensorNoise) {
  // Given the Experiment-1 drive with the accelerometer, torque, speed and pressure noise of
  // production sensors (which pulls the unfiltered paper block 13 % low), the 1 Hz low-pass,
  // 0.4 s differences and NIG land within 1.5 % (issue 8: 1-2.6 % on well-excited drives of a
  // more realistic simulator; measured here over seeds 1-6: at most 0.9 % over the last quarter).
  DriveSpec spec = paper_experiment1_drive();
  spec.sensors = car_sensor_noise();
  const DriveLog log = simulate_drive(spec);
  const DriveResult r = run_baseline("paper_lp", nominal_of(spec.car, 1500.0), log.samples, 1659.0);
  EXPECT_LT(std::abs(r.final_error), 0.015);
  EXPECT_LT(r.worst_error_late, 0.015);
  EXPECT_TRUE(r.final_estimate.has_interval);
}

TEST(PaperLpBaseline, NeverFiltersOrDifferencesAcrossAHole) {
  const NominalVehicle car = exact_car(1500.0);
  std::vector<vmass::Sample> samples = exact_force_stream(car, 2000.0, 300.0, 0.0, 20.0);
  const auto after_gap = exact_force_stream(car, 2000.0, 5300.0, 23.0, 20.0);
  samples.insert(samples.end(), after_gap.begin(), after_gap.end());
  auto after_bad = exact_force_stream(car, 2000.0, -2700.0, 43.0, 20.0);
  after_bad[0].valid &= ~vmass::input_bit(vmass::Input::kSpeed);
  samples.insert(samples.end(), after_bad.begin(), after_bad.end());
  PaperLpBaseline b(car, 100.0);
  for (const auto& s : samples) b.step(s);
  EXPECT_NEAR(b.estimate().mass_kg, 2000.0, 0.001 * 2000.0);
}

}  // namespace
}  // namespace vmass::baselines

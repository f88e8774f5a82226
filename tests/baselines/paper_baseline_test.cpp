// PaperBaseline: exact on exact data, like the paper on a drive like its Experiment 1, and the
// data rules (holes, invalid inputs, no brake-pressure signal).
#include "vmass/baselines/paper_baseline.hpp"

#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "drive_cases.hpp"
#include "drive_checks.hpp"
#include "exact_streams.hpp"

namespace vmass::baselines {
namespace {

using namespace testing;

double run(PaperBaseline* b, const std::vector<vmass::Sample>& samples) {
  for (const auto& s : samples) b->step(s);
  return b->estimate().mass_kg;
}

TEST(PaperBaseline, ExactDataGiveTheMass) {
  // F = M a_x + 300 N exactly, braking included; started at the empty mass, 500 kg away.
  PaperBaseline b(exact_car(1500.0), 100.0);
  const double mass = run(&b, exact_force_stream(exact_car(1500.0), 2000.0, -300.0, 0.0, 60.0));
  EXPECT_NEAR(mass, 2000.0, 0.001 * 2000.0);  // the prior's pull is below 0.1 %
  EXPECT_NEAR(b.rls().theta()[1], 0.0, 1.0);  // mu: the offset cancels in a difference
  EXPECT_GT(b.estimate().updates, 4000);
  EXPECT_FALSE(b.estimate().has_interval);  // the paper's RLS gives none
}

TEST(PaperBaseline, LikeItsExperiment1) {
  // Given the paper's clean Experiment 1 (ECE-15 segment with a slope profile, 1659 kg), started
  // at 1500 kg. The paper reports a 0.38 % steady error and "less than 1 %"; we assert 1 % on
  // the final value and over the whole last quarter (measured: 0.03 %).
  const DriveSpec spec = paper_experiment1_drive();
  const DriveLog log = simulate_drive(spec);
  const DriveResult r = run_baseline("paper", nominal_of(spec.car, 1500.0), log.samples, 1659.0);
  EXPECT_LT(std::abs(r.final_error), 0.01);
  EXPECT_LT(r.worst_error_late, 0.01);
  EXPECT_TRUE(r.mass_throughout_late);
}

TEST(PaperBaseline, AsPublishedItIsPulledLowByAccelerometerNoise) {
  // The same drive with production sensor noise: unfiltered 0.2 s differences let noise-only
  // pairs through the 0.01 m/s^2 gate (errors in variables), as issue 8 found. This guards the
  // baseline against quietly gaining a filter. Measured over seeds 1-6: -12.7 % to -14.4 %.
  DriveSpec spec = paper_experiment1_drive();
  spec.sensors = car_sensor_noise();
  const DriveLog log = simulate_drive(spec);
  const DriveResult r = run_baseline("paper", nominal_of(spec.car, 1500.0), log.samples, 1659.0);
  EXPECT_LT(r.final_error, -0.05);
}

TEST(PaperBaseline, NeverDifferencesAcrossAHole) {
  // Three stretches whose force offsets differ by kilonewtons: a difference across the time gap
  // or across the invalid and the non-finite tick would see that jump as inertia.
  const NominalVehicle car = exact_car(1500.0);
  std::vector<vmass::Sample> samples = exact_force_stream(car, 2000.0, 300.0, 0.0, 20.0);
  const auto after_gap = exact_force_stream(car, 2000.0, 5300.0, 25.0, 20.0);
  samples.insert(samples.end(), after_gap.begin(), after_gap.end());
  auto after_bad = exact_force_stream(car, 2000.0, -2700.0, 45.0, 20.0);
  after_bad[0].valid &= ~vmass::input_bit(vmass::Input::kAccelX);  // invalid
  after_bad[1].wheel_torque_nm = std::numeric_limits<double>::quiet_NaN();
  after_bad[1].brake_pressure_pa = std::numeric_limits<double>::quiet_NaN();
  samples.insert(samples.end(), after_bad.begin(), after_bad.end());
  PaperBaseline b(car, 100.0);
  EXPECT_NEAR(run(&b, samples), 2000.0, 0.001 * 2000.0);
}

TEST(PaperBaseline, WithoutBrakePressureOnlyTractionTicksAreUsed) {
  // F swings from -2.9 kN (braking) to +2.3 kN. Without the pressure signal the braking ticks
  // cannot be told apart from coasting and are skipped; the traction ticks alone give the mass.
  const NominalVehicle car = exact_car(1500.0);
  const auto with_signal = exact_force_stream(car, 2000.0, -300.0, 0.0, 60.0);
  auto without = with_signal;
  for (auto& s : without) s.valid &= ~vmass::input_bit(vmass::Input::kBrakePressure);
  PaperBaseline full(car, 100.0), partial(car, 100.0);
  EXPECT_NEAR(run(&full, with_signal), 2000.0, 2.0);
  EXPECT_NEAR(run(&partial, without), 2000.0, 2.0);
  EXPECT_LT(partial.estimate().updates, full.estimate().updates * 3 / 4);
  EXPECT_GT(partial.estimate().updates, 0);
  // An unknown brake gain with the signal present: braking ticks skipped the same way.
  NominalVehicle no_gain = car;
  no_gain.brake_gain_n_per_pa = 0.0;
  PaperBaseline gainless(no_gain, 100.0);
  auto firm = with_signal;
  press_brakes_firmly(&firm);  // no brake force hides below the 0.2 bar "applied" threshold
  EXPECT_NEAR(run(&gainless, firm), 2000.0, 2.0);
  EXPECT_LT(gainless.estimate().updates, full.estimate().updates * 3 / 4);
}

}  // namespace
}  // namespace vmass::baselines

// Fathy2008Baseline: exact on exact data, like the paper on a passenger car driven hard, and the
// data its supervisor leaves out (braking, holes).
#include "vmass/baselines/fathy2008_baseline.hpp"

#include <cmath>

#include <gtest/gtest.h>

#include "drive_cases.hpp"
#include "drive_checks.hpp"
#include "exact_streams.hpp"

namespace vmass::baselines {
namespace {

using namespace testing;

TEST(Fathy2008Baseline, ExactDataGiveTheMassWithABoundAroundIt) {
  // F = M a_x + 3 kN (grade, rolling and drag together), always traction.
  Fathy2008Baseline b(exact_car(1500.0), 100.0);
  for (const auto& s : exact_force_stream(exact_car(1500.0), 2000.0, 3000.0, 0.0, 60.0)) b.step(s);
  const BaselineEstimate e = b.estimate();
  ASSERT_TRUE(e.has_mass);
  EXPECT_NEAR(e.mass_kg, 2000.0, 0.001 * 2000.0);
  ASSERT_TRUE(e.has_interval);
  EXPECT_LE(e.ci_low_kg, e.mass_kg);
  EXPECT_GE(e.ci_high_kg, e.mass_kg);
  EXPECT_LT(e.ci_high_kg - e.ci_low_kg, 0.01 * 2000.0);
  // The supervisor takes only the high-excitation samples, not every tick.
  EXPECT_GT(e.updates, 500);
  EXPECT_LT(e.updates, 5500);
}

TEST(Fathy2008Baseline, LikeItsPaperOnACarDrivenHard) {
  // Given a loaded 2 t SUV with repeated strong accelerations through the gears and hard braking
  // over grades up to 4 %, with production sensor noise, started at 1.7 t: within 3 % on the final
  // value and over the last quarter (measured over seeds 1-6: at most 1.3 %). The paper's own
  // accuracy figures could not be checked; 3 % is "a few percent" with margin over our seeds.
  const DriveSpec spec = fathy_car_drive();
  const DriveLog log = simulate_drive(spec);
  const DriveResult r =
      run_baseline("fathy2008", nominal_of(spec.car, 1700.0), log.samples, 2000.0);
  EXPECT_LT(std::abs(r.final_error), 0.03);
  EXPECT_LT(r.worst_error_late, 0.03);
  EXPECT_TRUE(r.final_estimate.has_interval);
}

TEST(Fathy2008Baseline, LeavesBrakingAndHolesOut) {
  // Braking stretches carry a brake force the method does not model: F = C / r would be wrong
  // there. A time gap with a jump of the resistive force must not pass the high-pass either.
  const NominalVehicle car = exact_car(1500.0);
  std::vector<vmass::Sample> samples = exact_force_stream(car, 2000.0, -300.0, 0.0, 60.0);
  press_brakes_firmly(&samples);  // no brake force hides below the 0.2 bar "applied" threshold
  const auto after_gap = exact_force_stream(car, 2000.0, 4000.0, 62.0, 30.0);
  samples.insert(samples.end(), after_gap.begin(), after_gap.end());
  Fathy2008Baseline b(car, 100.0);
  for (const auto& s : samples) b.step(s);
  EXPECT_NEAR(b.estimate().mass_kg, 2000.0, 0.001 * 2000.0);
}

}  // namespace
}  // namespace vmass::baselines

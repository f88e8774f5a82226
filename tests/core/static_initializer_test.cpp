// Given a standing vehicle with a known extra load, when the deflection settles, then eq. (3)
// gives the mass; when the load changes at standstill, a new initial mass is reported.
#include "vmass/core/static_initializer.hpp"

#include <random>

#include <gtest/gtest.h>

namespace vmass {
namespace {

VehicleParams test_vehicle() {
  VehicleParams v;
  v.empty_mass_kg = 1500.0;
  v.wheelbase_m = 2.7;
  v.cg_to_front_axle_m = 1.2;
  v.wheel_radius_m = 0.31;
  v.brake_gain_n_per_pa = 3e-3;
  v.steering_ratio = 15.0;
  v.cornering_stiffness_front_n_per_rad = 1.5e5;
  v.cornering_stiffness_rear_n_per_rad = 1.7e5;
  return v;
}

SuspensionParams test_suspension() {
  SuspensionParams s;
  s.stiffness_n_per_m = 30000.0;
  s.empty_deflection_m = 0.010;
  return s;
}

// Deflection that eq. (3) maps to `mass_kg` with the linear spring.
double deflection_for(double mass_kg, const VehicleParams& v, const SuspensionParams& s) {
  return s.empty_deflection_m + (mass_kg - v.empty_mass_kg) * v.cg_to_front_axle_m *
                                    v.gravity_mps2 / (2.0 * v.wheelbase_m * s.stiffness_n_per_m);
}

// The paper's eq. (3) alone: every load sits at the centre of gravity (over-read factor 1).
StaticInitParams load_at_centre_of_gravity(const VehicleParams& v) {
  StaticInitParams p;
  p.payload_x_min_fraction = v.cg_to_front_axle_m / v.wheelbase_m;
  p.payload_x_max_fraction = p.payload_x_min_fraction;
  p.payload_y_max_fraction = 0.0;
  return p;
}

Sample standing(TimeUs t, double deflection_m) {
  Sample s;
  s.time_us = t;
  s.set(Input::kSpeed, 0.0);
  s.set(Input::kRearRightDeflection, deflection_m);
  return s;
}

TEST(StaticInitializer, Eq3MatchesHandComputation) {
  const VehicleParams v = test_vehicle();
  const SuspensionParams s = test_suspension();
  StaticInitializer init(v, s, StaticInitParams{});
  // 2.64 mm as in the paper's road test: 2 l c dz / (l_f g) by hand.
  const double expected = 1500.0 + 2.0 * 2.7 * 30000.0 * 0.00264 / (1.2 * 9.80665);
  EXPECT_NEAR(init.mass_from_deflection_kg(0.010 + 0.00264), expected, 1e-9);
}

TEST(StaticInitializer, AveragesNoisyStandstillWindow) {
  const VehicleParams v = test_vehicle();
  const SuspensionParams s = test_suspension();
  StaticInitializer init(v, s, load_at_centre_of_gravity(v));
  std::mt19937_64 rng(7);
  std::normal_distribution<double> noise(0.0, 0.0003);
  const double z = deflection_for(1700.0, v, s);
  std::optional<StaticMass> result;
  TimeUs t = 0;
  for (; t < 10 * kUsPerSecond && !result; t += 10'000)
    result = init.step(standing(t, z + noise(rng)));
  ASSERT_TRUE(result.has_value());
  EXPECT_FALSE(result->load_changed);
  // 1 s settle + 2 s window.
  EXPECT_NEAR(to_seconds(result->time_us), 3.0, 0.02);
  // 200 samples of 0.3 mm noise: the mean is within ~0.1 mm, i.e. ~1.5 kg.
  EXPECT_NEAR(result->prior.mass_kg, 1700.0, 3.0);
  // Where the load sits is known here: the base 40 kg only.
  EXPECT_NEAR(result->prior.mass_std_kg, 40.0, 1e-9);
}

TEST(StaticInitializer, MovingResetsTheWindow) {
  const VehicleParams v = test_vehicle();
  const SuspensionParams s = test_suspension();
  StaticInitializer init(v, s, StaticInitParams{});
  const double z = deflection_for(1600.0, v, s);
  TimeUs t = 0;
  for (; t < 2'500'000; t += 10'000) ASSERT_FALSE(init.step(standing(t, z)));
  Sample rolling = standing(t, z);
  rolling.speed_mps = 1.0;
  ASSERT_FALSE(init.step(rolling));
  // A new settle + window must pass before anything is reported.
  std::optional<StaticMass> result;
  const TimeUs restart = t + 10'000;
  for (t = restart; !result; t += 10'000) result = init.step(standing(t, z));
  EXPECT_GE(to_seconds(result->time_us - restart), 3.0 - 1e-9);
}

TEST(StaticInitializer, ReportsLoadChangeBeyondNoiseOnly) {
  const VehicleParams v = test_vehicle();
  const SuspensionParams s = test_suspension();
  StaticInitializer init(v, s, load_at_centre_of_gravity(v));
  std::mt19937_64 rng(11);
  std::normal_distribution<double> noise(0.0, 0.0001);
  TimeUs t = 0;
  auto stand_for = [&](double seconds, double mass_kg) {
    std::optional<StaticMass> last;
    const TimeUs end = t + from_seconds(seconds);
    for (; t < end; t += 10'000) {
      if (auto r = init.step(standing(t, deflection_for(mass_kg, v, s) + noise(rng)))) last = r;
    }
    return last;
  };
  auto first = stand_for(4.0, 1600.0);
  ASSERT_TRUE(first);
  EXPECT_FALSE(first->load_changed);
  // Same load, a few more windows: nothing new.
  EXPECT_FALSE(stand_for(10.0, 1600.0));
  // +250 kg while standing (someone loads the boot): the new load is reported.
  auto changed = stand_for(10.0, 1850.0);
  ASSERT_TRUE(changed);
  EXPECT_TRUE(changed->load_changed);
  EXPECT_NEAR(changed->prior.mass_kg, 1850.0, 2.0);
}

TEST(StaticInitializer, UnsettledWindowIsDiscarded) {
  const VehicleParams v = test_vehicle();
  const SuspensionParams s = test_suspension();
  StaticInitParams p;
  StaticInitializer init(v, s, p);
  // The body rocks with 5 mm amplitude (people getting in): no window completes.
  for (TimeUs t = 0; t < 20 * kUsPerSecond; t += 10'000) {
    const double rocking = 0.005 * std::sin(2.0 * 3.14159 * 1.5 * to_seconds(t));
    ASSERT_FALSE(init.step(standing(t, 0.02 + rocking)));
  }
}

TEST(StaticInitializer, ProgressiveCurveAndRangeWidenPrior) {
  const VehicleParams v = test_vehicle();
  SuspensionParams s = test_suspension();
  s.progressive_knee_m = 0.030;
  s.progressive_rate_n_per_m2 = 2.0e6;
  s.calibrated_range_kg = 600.0;
  StaticInitializer init(v, s, load_at_centre_of_gravity(v));
  const double z = 0.045;
  const double force = 30000.0 * (z - 0.010) + 2.0e6 * (z - 0.030) * (z - 0.030);
  const double expected = 1500.0 + 2.0 * 2.7 * force / (1.2 * 9.80665);
  const StaticMass m = init.static_mass_for(z, 0.0);
  EXPECT_NEAR(m.prior.mass_kg, expected, 1e-9);
  EXPECT_GT(m.added_mass_kg, 600.0);
  EXPECT_TRUE(m.beyond_calibrated_range);
  EXPECT_DOUBLE_EQ(m.prior.mass_std_kg, StaticInitParams{}.out_of_range_prior_std_kg);
}

// One rear corner's sensor reads a load at x behind the front axle and y across as
// (x / l_f)(1 - 2 y / track) of it: the boot over-reads 2-3x, the far-side seat under-reads.
// Over the placements of the default band the prior's 95 % interval holds the truth about 95 %
// of the time (a normal prior cannot cover the band's extreme corners), and for a load in the
// boot the prior is nearer than eq. (3).
TEST(StaticInitializer, PayloadAnywhereInTheCabinOrBootIsInsideThePriorsInterval) {
  const VehicleParams v = test_vehicle();
  const SuspensionParams s = test_suspension();
  const StaticInitParams p;
  StaticInitializer init(v, s, p);
  const double load_kg = 300.0;
  const double true_mass = v.empty_mass_kg + load_kg;
  int covered = 0, placements = 0;
  for (int i = 0; i <= 20; ++i) {
    for (int j = 0; j <= 10; ++j) {
      const double x = p.payload_x_min_fraction +
                       (p.payload_x_max_fraction - p.payload_x_min_fraction) * i / 20.0;
      const double u = p.payload_y_max_fraction * (j / 5.0 - 1.0);
      const double over_read = x * v.wheelbase_m / v.cg_to_front_axle_m * (1.0 - 2.0 * u);
      const double eq3_mass = v.empty_mass_kg + over_read * load_kg;
      const StaticMass m = init.static_mass_for(deflection_for(eq3_mass, v, s), 0.0);
      covered += std::abs(m.prior.mass_kg - true_mass) < 1.96 * m.prior.mass_std_kg;
      ++placements;
    }
  }
  EXPECT_GE(covered, 0.9 * placements);
  // In the boot (x = l): eq. (3) reads 2.25 x the load; the prior is nearer.
  const double boot_eq3 = v.empty_mass_kg + v.wheelbase_m / v.cg_to_front_axle_m * load_kg;
  const StaticMass boot = init.static_mass_for(deflection_for(boot_eq3, v, s), 0.0);
  EXPECT_LT(std::abs(boot.prior.mass_kg - true_mass), std::abs(boot_eq3 - true_mass));
  EXPECT_GT(init.payload_factor_mean(), 0.0);
  EXPECT_LT(init.payload_factor_mean(), 1.0);  // the band lies mostly behind l_f
}

TEST(StaticInitializer, InvalidDeflectionNeverInitialises) {
  StaticInitializer init(test_vehicle(), test_suspension(), StaticInitParams{});
  for (TimeUs t = 0; t < 10 * kUsPerSecond; t += 10'000) {
    Sample s = standing(t, 0.02);
    s.valid &= ~input_bit(Input::kRearRightDeflection);
    ASSERT_FALSE(init.step(s));
    Sample nan = standing(t, std::nan(""));
    ASSERT_FALSE(init.step(nan));
  }
}

}  // namespace
}  // namespace vmass

namespace vmass {
namespace {

TEST(StaticInitializer, AnotherGradeIsNotALoadChange) {
  const VehicleParams v = test_vehicle();
  const SuspensionParams s = test_suspension();
  StaticInitializer init(v, s, StaticInitParams{});
  TimeUs t = 0;
  // deflection_mm shift stands for the load moved between axles by the slope.
  auto stand = [&](double seconds, double deflection_m, double grade_accel) {
    std::optional<StaticMass> last;
    const TimeUs end = t + from_seconds(seconds);
    for (; t < end; t += 10'000) {
      Sample x = standing(t, deflection_m);
      x.set(Input::kAccelX, grade_accel);
      if (auto r = init.step(x)) last = r;
    }
    return last;
  };
  const double level = deflection_for(1650.0, v, s);
  ASSERT_TRUE(stand(4.0, level, 0.0));
  // Parked on a 3 % slope: the rear deflection moves by 1.2 mm, the load did not change.
  EXPECT_FALSE(stand(10.0, level + 0.0012, 0.29));
  // Back on the level with the same load: nothing.
  EXPECT_FALSE(stand(10.0, level, 0.01));
  // On the level again with +150 kg: a load change.
  auto changed = stand(10.0, deflection_for(1800.0, v, s), 0.0);
  ASSERT_TRUE(changed);
  EXPECT_TRUE(changed->load_changed);
  EXPECT_NEAR(changed->grade_accel_mps2, 0.0, 1e-12);
}

}  // namespace
}  // namespace vmass

// Given a drive with a known mass on a varying grade with drag and rolling resistance, the
// differenced pairs (eq. 5) regress to that mass: the resistive forces cancel.
#include "vmass/core/longitudinal_extractor.hpp"

#include <cmath>
#include <random>

#include <gtest/gtest.h>
#include <Eigen/Dense>

#include "synthetic_drive.hpp"

namespace vmass {
namespace {

using testing::LongitudinalDrive;

// Ordinary least squares of y = M da + mu over the pairs (independent of the regressors).
Eigen::Vector2d batch_fit(const std::vector<RegressionPair>& pairs) {
  Eigen::MatrixXd phi(pairs.size(), 2);
  Eigen::VectorXd y(pairs.size());
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    phi(static_cast<Eigen::Index>(i), 0) = pairs[i].delta_accel_mps2;
    phi(static_cast<Eigen::Index>(i), 1) = 1.0;
    y(static_cast<Eigen::Index>(i)) = pairs[i].y_n;
  }
  return phi.colPivHouseholderQr().solve(y);
}

std::vector<RegressionPair> extract(const std::vector<Sample>& samples, const VehicleParams& v,
                                    const LongitudinalParams& p, const DifferencingParams& d) {
  LongitudinalExtractor ex(v, p, d);
  std::vector<RegressionPair> pairs;
  for (const Sample& s : samples) {
    const Extraction e = ex.step(s);
    if (e.has_pair()) pairs.push_back(e.pair);
    // Pairs kept until the lag was identified come out once it is.
    Extraction released;
    while (ex.pop_released(&released)) {
      if (released.has_pair()) pairs.push_back(released.pair);
    }
  }
  return pairs;
}

TEST(LongitudinalExtractor, SlopeAndDragCancelInDifferences) {
  const VehicleParams v = testing::test_vehicle();
  LongitudinalDrive drive;
  const auto samples = testing::longitudinal_samples(drive, v, 0.0, 120.0, 15.0, 0.01);
  const auto pairs = extract(samples, v, LongitudinalParams{}, DifferencingParams{});
  ASSERT_GT(pairs.size(), 5000u);
  const Eigen::Vector2d theta = batch_fit(pairs);
  // Residual of differencing: drag changes by 2 k v dv and the grade term is felt by M only
  // (the rotating mass correction adds m_rot g d(sin grade)); both are tiny at dt = 0.02 s.
  EXPECT_NEAR(theta(0), drive.mass_kg, 0.002 * drive.mass_kg);
  EXPECT_NEAR(theta(1), 0.0, 5.0);
}

TEST(LongitudinalExtractor, WithoutRotatingMassCorrectionTheMassIsBiased) {
  VehicleParams v = testing::test_vehicle();
  LongitudinalDrive drive;
  const auto samples = testing::longitudinal_samples(drive, v, 0.0, 60.0, 15.0, 0.01);
  v.rotating_mass_kg = 0.0;  // the paper's model
  const Eigen::Vector2d theta =
      batch_fit(extract(samples, v, LongitudinalParams{}, DifferencingParams{}));
  EXPECT_NEAR(theta(0), drive.mass_kg + drive.rotating_mass_kg, 0.002 * drive.mass_kg);
}

TEST(LongitudinalExtractor, LongerDifferencingStepStillCancelsResistance) {
  const VehicleParams v = testing::test_vehicle();
  LongitudinalDrive drive;
  const auto samples = testing::longitudinal_samples(drive, v, 0.0, 120.0, 15.0, 0.01);
  DifferencingParams d;
  d.differencing_dt_s = 0.2;  // the paper's CAN setting
  const Eigen::Vector2d theta = batch_fit(extract(samples, v, LongitudinalParams{}, d));
  EXPECT_NEAR(theta(0), drive.mass_kg, 0.005 * drive.mass_kg);
}

// The synthetic drive's decelerations as negative wheel torque instead of brake pressure, the
// torque reported `report_scale` times the true one.
std::vector<Sample> decelerating_without_brakes(std::vector<Sample> samples, const VehicleParams& v,
                                                double report_scale) {
  for (Sample& s : samples) {
    if (!(s.brake_pressure_pa > 0.0)) continue;
    const double force_n = -s.brake_pressure_pa * v.brake_gain_n_per_pa;
    s.set(Input::kWheelTorque, report_scale * force_n * v.wheel_radius_m);
    s.set(Input::kBrakePressure, 0.0);
  }
  return samples;
}

// Given an ECU whose drag torque in overrun reads 30 % high (its friction model), the pairs
// that saw a negative torque would bias the mass; none is taken. An electric drive's negative
// torque (regeneration) is as good as its drive torque: its pairs are taken.
TEST(LongitudinalExtractor, AnEngineDraggedInOverrunGivesNoPair) {
  const VehicleParams combustion = testing::test_vehicle();
  LongitudinalDrive drive;
  const std::vector<Sample> braking =
      testing::longitudinal_samples(drive, combustion, 0.0, 120.0, 15.0, 0.01);
  const auto overrun = decelerating_without_brakes(braking, combustion, 1.3);
  const auto pairs = extract(overrun, combustion, LongitudinalParams{}, DifferencingParams{});
  ASSERT_GT(pairs.size(), 1000u);
  EXPECT_NEAR(batch_fit(pairs)(0), drive.mass_kg, 0.005 * drive.mass_kg);
  LongitudinalParams with_overrun;
  with_overrun.use_overrun = true;
  const auto biased = extract(overrun, combustion, with_overrun, DifferencingParams{});
  EXPECT_GT(biased.size(), pairs.size());
  EXPECT_GT(std::abs(batch_fit(biased)(0) - drive.mass_kg), 0.02 * drive.mass_kg);

  VehicleParams electric = combustion;
  electric.electric_drive = true;
  const auto regenerating = decelerating_without_brakes(braking, electric, 1.0);
  const auto electric_pairs =
      extract(regenerating, electric, LongitudinalParams{}, DifferencingParams{});
  EXPECT_GT(electric_pairs.size(), pairs.size());
  EXPECT_NEAR(batch_fit(electric_pairs)(0), drive.mass_kg, 0.005 * drive.mass_kg);
}

// Given an accelerometer that over-reads by 3 % (a body that pitches 1.7 deg/g) and a speed
// signal that jitters, accel_source: calibrated learns the 3 % from the wheel speed and
// the mass comes out right: the noise in the wheel-speed derivative does not attenuate it.
TEST(LongitudinalExtractor, TheCalibratedSourceLearnsTheAccelerometersScale) {
  const VehicleParams v = testing::test_vehicle();
  LongitudinalDrive drive;
  drive.grade_rad = [](double) { return 0.0; };
  std::vector<Sample> samples = testing::longitudinal_samples(drive, v, 0.0, 300.0, 15.0, 0.01);
  // Wheel speeds jitter with slip and the tyre's tread (0.1 m/s here) and come in 0.01 m/s steps.
  std::mt19937_64 rng(7);
  std::normal_distribution<double> jitter_mps(0.0, 0.1);
  for (Sample& s : samples) {
    s.set(Input::kAccelX, 1.03 * s.accel_x_mps2);
    s.set(Input::kSpeed, std::round((s.speed_mps + jitter_mps(rng)) / 0.01) * 0.01);
  }
  LongitudinalParams calibrated;
  calibrated.accel_source = AccelSource::kCalibrated;
  LongitudinalExtractor ex(v, calibrated, DifferencingParams{});
  std::vector<RegressionPair> pairs;
  for (const Sample& s : samples) {
    const Extraction e = ex.step(s);
    if (e.has_pair() && s.time_us > from_seconds(150.0)) pairs.push_back(e.pair);
    Extraction released;
    while (ex.pop_released(&released)) {
    }
  }
  EXPECT_NEAR(ex.accel_scale(), 1.03, 0.005);
  ASSERT_GT(pairs.size(), 1000u);
  EXPECT_NEAR(batch_fit(pairs)(0), drive.mass_kg, 0.01 * drive.mass_kg);
}

// The speed as an instrument cluster shows it: refreshed every 100 ms in 0.5 km/h steps,
// 0.2 s late.
std::vector<Sample> with_cluster_speed(std::vector<Sample> samples) {
  constexpr double kStepMps = 0.5 / 3.6;
  constexpr std::size_t kLateTicks = 20, kFrameTicks = 10;
  std::vector<double> true_speed;
  for (const Sample& s : samples) true_speed.push_back(s.speed_mps);
  double shown = true_speed.front();
  for (std::size_t i = 0; i < samples.size(); ++i) {
    if (i % kFrameTicks == 0 && i >= kLateTicks) {
      shown = std::round(true_speed[i - kLateTicks] / kStepMps) * kStepMps;
    }
    samples[i].set(Input::kSpeed, shown);
  }
  return samples;
}

// Given a truck's first gear (rotating masses 80 % of the vehicle's own) and only the cluster's
// speed, that speed's derivative misses part of the wheels' acceleration change and the mass
// reads high; the extractor sees the signal is coarse and takes the rotating term from the
// accelerometer (rotating_accel_source: auto), and the mass comes out right. With an ESC's speed
// it keeps the wheel speed.
TEST(LongitudinalExtractor, ACoarseSpeedSignalLeavesTheRotatingTermToTheAccelerometer) {
  VehicleParams v = testing::test_vehicle();
  LongitudinalDrive drive;
  drive.rotating_mass_kg = 0.8 * drive.mass_kg;
  v.rotating_mass_kg = drive.rotating_mass_kg;
  const auto esc = testing::longitudinal_samples(drive, v, 0.0, 120.0, 15.0, 0.01);
  const auto cluster = with_cluster_speed(esc);

  const auto auto_pairs = extract(cluster, v, LongitudinalParams{}, DifferencingParams{});
  ASSERT_GT(auto_pairs.size(), 3000u);
  EXPECT_NEAR(batch_fit(auto_pairs)(0), drive.mass_kg, 0.01 * drive.mass_kg);

  LongitudinalParams wheel_speed;
  wheel_speed.rotating_accel_source = RotatingAccelSource::kWheelSpeed;
  const auto late_pairs = extract(cluster, v, wheel_speed, DifferencingParams{});
  EXPECT_GT(std::abs(batch_fit(late_pairs)(0) - drive.mass_kg), 0.05 * drive.mass_kg);

  // The ESC's speed: exactly the wheel speed's pairs.
  const auto esc_auto = extract(esc, v, LongitudinalParams{}, DifferencingParams{});
  const auto esc_wheel = extract(esc, v, wheel_speed, DifferencingParams{});
  ASSERT_EQ(esc_auto.size(), esc_wheel.size());
  for (std::size_t i = 0; i < esc_auto.size(); ++i) EXPECT_EQ(esc_auto[i].y_n, esc_wheel[i].y_n);
  EXPECT_NEAR(batch_fit(esc_auto)(0), drive.mass_kg, 0.005 * drive.mass_kg);
}

TEST(LongitudinalExtractor, GatesOfTableII) {
  const VehicleParams v = testing::test_vehicle();
  LongitudinalExtractor ex(v, LongitudinalParams{}, DifferencingParams{});
  LongitudinalDrive drive;
  auto samples = testing::longitudinal_samples(drive, v, 0.0, 5.0, 15.0, 0.01);
  // Lateral acceleration above the gate blocks every pair.
  for (Sample& s : samples) s.accel_y_mps2 = LongitudinalParams{}.max_abs_accel_y_mps2 + 0.05;
  for (const Sample& s : samples) {
    const Extraction e = ex.step(s);
    EXPECT_FALSE(e.has_pair());
  }
  // Constant speed: |da_x| below its gate -> no pair.
  LongitudinalExtractor cruise(v, LongitudinalParams{}, DifferencingParams{});
  LongitudinalDrive flat;
  flat.accel_mps2 = [](double) { return 0.0; };
  flat.grade_rad = [](double) { return 0.0; };
  int small = 0;
  for (const Sample& s : testing::longitudinal_samples(flat, v, 0.0, 5.0, 20.0, 0.01)) {
    const Extraction e = cruise.step(s);
    EXPECT_FALSE(e.has_pair());
    small += e.verdict == PairVerdict::kSmallDeltaAccel;
  }
  // Every tick after the first window and its settle time.
  const int warm_up_ticks = static_cast<int>(
      (DifferencingParams{}.differencing_dt_s + LongitudinalParams{}.settle_s) * 100.0);
  EXPECT_GE(small, 500 - warm_up_ticks - 2);
}

TEST(LongitudinalExtractor, GearChangeInsideWindowIsRejected) {
  const VehicleParams v = testing::test_vehicle();
  LongitudinalExtractor ex(v, LongitudinalParams{}, DifferencingParams{});
  LongitudinalDrive drive;
  auto samples = testing::longitudinal_samples(drive, v, 0.0, 4.0, 15.0, 0.01);
  constexpr std::size_t kShift = 200;
  for (std::size_t i = 0; i < samples.size(); ++i) samples[i].set(Input::kGear, i < kShift ? 2 : 3);
  // A shift ends the clean stretch: no pair until a whole window and its settle time have
  // passed in the new gear.
  const auto quiet_ticks = static_cast<std::size_t>(
      (DifferencingParams{}.differencing_dt_s + LongitudinalParams{}.settle_s) * 100.0);
  int accepted_before = 0;
  for (std::size_t i = 0; i < samples.size(); ++i) {
    const Extraction e = ex.step(samples[i]);
    if (i < kShift) accepted_before += e.has_pair() || e.verdict == PairVerdict::kAwaitingLag;
    if (i >= kShift && i < kShift + quiet_ticks) {
      EXPECT_FALSE(e.has_pair()) << i;
      EXPECT_NE(e.verdict, PairVerdict::kAwaitingLag) << i;
    }
  }
  EXPECT_GT(accepted_before, 0);  // the stretch before the shift was usable
}

// An engine-torque-only car in neutral, or a frame with a NaN: a tick the block cannot use. No
// window may span it, but the pairs already held for the lag were complete before it; dropping
// them lost the provisional estimate at every gear shift of such a car.
TEST(LongitudinalExtractor, HeldPairsOutliveAHoleInTheData) {
  const VehicleParams v = testing::test_vehicle();
  LongitudinalExtractor ex(v, LongitudinalParams{}, DifferencingParams{});
  LongitudinalDrive drive;
  auto samples = testing::longitudinal_samples(drive, v, 0.0, 3.0, 15.0, 0.01);
  constexpr std::size_t kHole = 250;
  samples[kHole].set(Input::kWheelTorque, std::nan(""));
  std::size_t held_before_hole = 0;
  for (std::size_t i = 0; i < samples.size(); ++i) {
    const Extraction e = ex.step(samples[i]);
    if (i + 1 == kHole) held_before_hole = ex.pending_count();
    if (i == kHole) {
      EXPECT_EQ(e.verdict, PairVerdict::kNonFinite);
      EXPECT_EQ(ex.pending_count(), held_before_hole);
    }
  }
  ASSERT_FALSE(ex.lag().identified());  // every pair so far is held
  EXPECT_GT(held_before_hole, 0u);
  EXPECT_GE(ex.pending_count(), held_before_hole);
  ex.reset();  // a restart (a load that may have changed) does drop them
  EXPECT_EQ(ex.pending_count(), 0u);
}

TEST(LongitudinalExtractor, NeverDifferencesAcrossInvalidOrNonFiniteInputs) {
  const VehicleParams v = testing::test_vehicle();
  LongitudinalExtractor ex(v, LongitudinalParams{}, DifferencingParams{});
  LongitudinalDrive drive;
  auto samples = testing::longitudinal_samples(drive, v, 0.0, 3.0, 15.0, 0.01);
  samples[150].valid &= ~input_bit(Input::kAccelX);
  samples[200].wheel_torque_nm = std::nan("");
  for (std::size_t i = 0; i < samples.size(); ++i) {
    const Extraction e = ex.step(samples[i]);
    if (i == 150) {
      EXPECT_EQ(e.verdict, PairVerdict::kInputsInvalid);
    }
    if (i == 200) {
      EXPECT_EQ(e.verdict, PairVerdict::kNonFinite);
    }
    // The two ticks after a hole have no history dt back.
    if (i == 151 || i == 152 || i == 201 || i == 202) {
      EXPECT_EQ(e.verdict, PairVerdict::kWarmingUp);
    }
    if (e.has_pair()) {
      EXPECT_TRUE(std::isfinite(e.pair.y_n));
    }
  }
}

TEST(LongitudinalExtractor, TimeGapIsNotDifferenced) {
  const VehicleParams v = testing::test_vehicle();
  LongitudinalExtractor ex(v, LongitudinalParams{}, DifferencingParams{});
  LongitudinalDrive drive;
  auto samples = testing::longitudinal_samples(drive, v, 0.0, 3.0, 15.0, 0.01);
  for (std::size_t i = 120; i < samples.size(); ++i) samples[i].time_us += 50'000;  // 50 ms hole
  for (std::size_t i = 0; i < samples.size(); ++i) {
    const Extraction e = ex.step(samples[i]);
    if (i == 120 || i == 121) {
      EXPECT_EQ(e.verdict, PairVerdict::kTimeGap) << i;
    }
  }
}

}  // namespace
}  // namespace vmass

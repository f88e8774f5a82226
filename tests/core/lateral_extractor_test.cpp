// Given a single-track vehicle of known mass slaloming at constant speed, the lateral pairs
// (eq. 9) regress to that mass; the gates of Table III hold.
#include "vmass/core/lateral_extractor.hpp"

#include <gtest/gtest.h>
#include <Eigen/Dense>

#include "synthetic_drive.hpp"

namespace vmass {
namespace {

// The lateral block is off by default (docs/estimator.md); these tests are about the block.
LateralParams enabled_lateral() {
  LateralParams p;
  p.enabled = true;
  return p;
}

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

TEST(LateralExtractor, SlalomRegressesToTheMass) {
  const VehicleParams v = testing::test_vehicle();
  testing::BicycleDrive drive;
  const auto samples = testing::bicycle_samples(drive, v, 0.0, 60.0, 0.01);
  LateralExtractor ex(v, enabled_lateral(), DifferencingParams{});
  std::vector<RegressionPair> pairs;
  for (const Sample& s : samples) {
    const Extraction e = ex.step(s);
    if (e.has_pair()) {
      EXPECT_EQ(e.pair.block, Block::kLateral);
      pairs.push_back(e.pair);
    }
  }
  ASSERT_GT(pairs.size(), 1000u);
  const Eigen::Vector2d theta = batch_fit(pairs);
  EXPECT_NEAR(theta(0), drive.mass_kg, 0.003 * drive.mass_kg);
}

TEST(LateralExtractor, SmallSteeringAngleYieldsNoPair) {
  const VehicleParams v = testing::test_vehicle();
  testing::BicycleDrive drive;
  drive.steering_wheel_rad = [](double t) { return 0.2 * std::sin(2.0 * 3.14159 * 0.4 * t); };
  LateralExtractor ex(v, enabled_lateral(), DifferencingParams{});  // 0.2 rad = 11.5 deg < 15
  for (const Sample& s : testing::bicycle_samples(drive, v, 0.0, 10.0, 0.01)) {
    EXPECT_FALSE(ex.step(s).has_pair());
  }
}

TEST(LateralExtractor, AcceleratingVehicleIsNotPureLateral) {
  const VehicleParams v = testing::test_vehicle();
  testing::BicycleDrive drive;
  auto samples = testing::bicycle_samples(drive, v, 0.0, 10.0, 0.01);
  for (Sample& s : samples) s.accel_x_mps2 += 1.0;  // v_x not constant
  LateralExtractor ex(v, enabled_lateral(), DifferencingParams{});
  for (const Sample& s : samples) EXPECT_FALSE(ex.step(s).has_pair());
}

TEST(LateralExtractor, LowSpeedYieldsNoPairAndNoNaN) {
  const VehicleParams v = testing::test_vehicle();
  testing::BicycleDrive drive;
  auto samples = testing::bicycle_samples(drive, v, 0.0, 5.0, 0.01);
  for (Sample& s : samples) s.speed_mps = 0.0;
  LateralExtractor ex(v, enabled_lateral(), DifferencingParams{});
  for (const Sample& s : samples) {
    const Extraction e = ex.step(s);
    EXPECT_EQ(e.verdict, PairVerdict::kSpeed);
  }
}

TEST(LateralVelocityFilter, TracksLateralVelocityOfTheSlalom) {
  const VehicleParams v = testing::test_vehicle();
  testing::BicycleDrive drive;
  // Re-integrate the model to have the true v_y at each sample time.
  const auto samples = testing::bicycle_samples(drive, v, 0.0, 20.0, 0.01);
  LateralVelocityFilter filter(LateralVelocityFilterParams{});
  double previous = 0.0;
  double max_abs_change_error = 0.0;
  for (std::size_t i = 0; i < samples.size(); ++i) {
    const Sample& s = samples[i];
    filter.step(i == 0 ? 0.0 : 0.01, s.accel_x_mps2, s.accel_y_mps2, s.yaw_rate_radps, s.speed_mps);
    // Kinematics: dv_y/dt = a_y - r v_x; the filter's change per step must follow it.
    if (i > 0) {
      const double expected_change = (s.accel_y_mps2 - s.yaw_rate_radps * s.speed_mps) * 0.01;
      const double change = filter.lateral_velocity_mps() - previous;
      max_abs_change_error = std::max(max_abs_change_error, std::abs(change - expected_change));
    }
    previous = filter.lateral_velocity_mps();
  }
  EXPECT_LT(max_abs_change_error, 2e-3);
  EXPECT_TRUE(std::isfinite(filter.lateral_velocity_mps()));
}

}  // namespace
}  // namespace vmass

// The sign convention of lateral_forces.hpp, proven with a steady turn whose answer is known:
// for a vehicle of mass M on a circle of radius R at speed v, the linear single-track model in
// equilibrium has a_y = v^2 / R, r = v / R and axle forces in moment balance. We solve that
// equilibrium independently (fixed point on the road-wheel angle), then check that
// axle_lateral_forces gives F_yf cos(delta) + F_yr = M a_y with the ISO 8855 signs: a left turn
// has positive steering, yaw rate, lateral acceleration and lateral force.
#include "vmass/core/lateral_forces.hpp"

#include <cmath>

#include <gtest/gtest.h>

#include "synthetic_drive.hpp"

namespace vmass {
namespace {

struct SteadyTurn {
  double yaw_rate_radps, lateral_velocity_mps, road_wheel_angle_rad, accel_y_mps2;
};

// Equilibrium of the linear single-track model on a circle; radius > 0 turns left.
SteadyTurn solve_steady_turn(const VehicleParams& v, double mass_kg, double speed_mps,
                             double radius_m) {
  const double lf = v.cg_to_front_axle_m, lr = v.cg_to_rear_axle_m(), l = v.wheelbase_m;
  SteadyTurn s{};
  s.yaw_rate_radps = speed_mps / radius_m;
  s.accel_y_mps2 = speed_mps * speed_mps / radius_m;
  // Moment balance: F_yf cos(delta) lf = F_yr lr; force balance: their sum is M a_y.
  const double fyr = mass_kg * s.accel_y_mps2 * lf / l;
  const double alpha_r = fyr / v.cornering_stiffness_rear_n_per_rad;
  // alpha_r = -atan(vy/vx) + lr r / vx
  s.lateral_velocity_mps = speed_mps * std::tan(lr * s.yaw_rate_radps / speed_mps - alpha_r);
  double delta = 0.0;
  for (int i = 0; i < 100; ++i) {
    const double fyf = mass_kg * s.accel_y_mps2 * lr / l / std::cos(delta);
    const double alpha_f = fyf / v.cornering_stiffness_front_n_per_rad;
    delta =
        alpha_f + std::atan(s.lateral_velocity_mps / speed_mps) + lf * s.yaw_rate_radps / speed_mps;
  }
  s.road_wheel_angle_rad = delta;
  return s;
}

TEST(LateralForces, SteadyLeftTurnGivesMassTimesLateralAcceleration) {
  const VehicleParams v = testing::test_vehicle();
  const double mass = 1650.0, speed = 15.0, radius = 80.0;
  const SteadyTurn turn = solve_steady_turn(v, mass, speed, radius);
  ASSERT_GT(turn.road_wheel_angle_rad, 0.0);  // steer left
  ASSERT_GT(turn.yaw_rate_radps, 0.0);        // yaw left
  const AxleLateralForces f = axle_lateral_forces(v, speed, turn.lateral_velocity_mps,
                                                  turn.yaw_rate_radps, turn.road_wheel_angle_rad);
  EXPECT_GT(f.front_n, 0.0);
  EXPECT_GT(f.rear_n, 0.0);
  EXPECT_NEAR(f.total_n, mass * turn.accel_y_mps2, 1e-6 * mass * turn.accel_y_mps2);
  EXPECT_NEAR(f.total_n / turn.accel_y_mps2, mass, 1e-6 * mass);
  // Moment balance about the centre of gravity.
  EXPECT_NEAR(f.front_n * std::cos(turn.road_wheel_angle_rad) * v.cg_to_front_axle_m,
              f.rear_n * v.cg_to_rear_axle_m(), 1e-6 * f.rear_n);
}

TEST(LateralForces, RightTurnMirrorsLeftTurn) {
  const VehicleParams v = testing::test_vehicle();
  const SteadyTurn left = solve_steady_turn(v, 1650.0, 20.0, 120.0);
  const SteadyTurn right = solve_steady_turn(v, 1650.0, 20.0, -120.0);
  EXPECT_LT(right.road_wheel_angle_rad, 0.0);
  EXPECT_NEAR(right.road_wheel_angle_rad, -left.road_wheel_angle_rad, 1e-12);
  const AxleLateralForces fl = axle_lateral_forces(v, 20.0, left.lateral_velocity_mps,
                                                   left.yaw_rate_radps, left.road_wheel_angle_rad);
  const AxleLateralForces fr = axle_lateral_forces(
      v, 20.0, right.lateral_velocity_mps, right.yaw_rate_radps, right.road_wheel_angle_rad);
  EXPECT_NEAR(fr.total_n, -fl.total_n, 1e-9 * std::abs(fl.total_n));
  EXPECT_NEAR(fr.total_n, 1650.0 * right.accel_y_mps2, 1e-6 * std::abs(fr.total_n));
}

TEST(LateralForces, ThePaperPrintedSignWouldGiveANegativeMass) {
  // Eq. (12) as printed is the negative of our slip angles: with it, F_lat / a_y = -M.
  const VehicleParams v = testing::test_vehicle();
  const SteadyTurn turn = solve_steady_turn(v, 1650.0, 15.0, 80.0);
  const AxleLateralForces f = axle_lateral_forces(v, 15.0, turn.lateral_velocity_mps,
                                                  turn.yaw_rate_radps, turn.road_wheel_angle_rad);
  const double paper_front = -f.slip_front_rad * v.cornering_stiffness_front_n_per_rad;
  const double paper_rear = -f.slip_rear_rad * v.cornering_stiffness_rear_n_per_rad;
  const double paper_total = paper_front * std::cos(turn.road_wheel_angle_rad) + paper_rear;
  EXPECT_NEAR(paper_total / turn.accel_y_mps2, -1650.0, 1e-3);
}

}  // namespace
}  // namespace vmass

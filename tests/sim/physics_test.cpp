// Physics of the simulated car checked against answers computed here, independently of the model
// code: resistive forces at constant speed, the accelerometer on a grade, a steady circle, the
// static suspension curve, rotating inertia.
#include <gtest/gtest.h>

#include <cmath>

#include "sim_test_util.hpp"
#include "vmass/sim/scenario.hpp"
#include "vmass/sim/simulator.hpp"

namespace vmass::sim {
namespace {

using test::ideal;
using test::run;
using test::straight_scenario;

constexpr double kG = 9.80665;

TEST(SimPhysics, FlatRoadConstantSpeedDriveForceEqualsDragPlusRolling) {
  // Given a straight flat road, 20 m/s, no noise
  const Scenario s = straight_scenario(20.0, 40.0);
  const SimulationResult r = run(s, ideal());
  // Then once settled the drive force is 0.5 rho CdA v^2 + f_r M g
  const double expected = 0.5 * 1.2 * 0.75 * 20.0 * 20.0 + 0.011 * 1659.0 * kG;
  int checked = 0;
  for (std::size_t k = 0; k < r.truth.size(); ++k) {
    if (to_seconds(r.truth[k].time_us) < 30.0) continue;
    EXPECT_NEAR(r.truth[k].speed_mps, 20.0, 0.01);
    EXPECT_NEAR(r.samples[k].wheel_torque_nm / 0.31, expected, 0.002 * expected);
    EXPECT_NEAR(r.truth[k].drag_force_n + r.truth[k].rolling_resistance_n, expected,
                1e-6 * expected);
    ++checked;
  }
  EXPECT_EQ(checked, 1001);
}

TEST(SimPhysics, StandingOnAGradeWithBrakesTheAccelerometerReadsGSinGrade) {
  for (double percent : {6.0, -4.0}) {
    // Given the car standing on a constant grade, brakes held
    Scenario s = straight_scenario(0.0, 10.0);
    const double grade = std::atan(percent / 100.0);
    s.road.grade_rad = PiecewiseLinear(grade);
    // When measured with ideal sensors
    const SimulationResult r = run(s, ideal());
    // Then a_x = g sin(grade) exactly and the car does not move
    for (std::size_t k = 0; k < r.samples.size(); ++k) {
      EXPECT_NEAR(r.samples[k].accel_x_mps2, kG * std::sin(grade), 1e-9);
      EXPECT_EQ(r.samples[k].speed_mps, 0.0);
      EXPECT_EQ(r.truth[k].distance_m, 0.0);
      EXPECT_GT(r.samples[k].brake_pressure_pa, 10e5);
    }
    // And with the real sensors the mean is g sin(grade) plus the documented bias
    SimulationOptions noisy;
    noisy.seed = 11;
    const SimulationResult rn = run(s, noisy);
    std::vector<double> ax;
    for (const Sample& smp : rn.samples) {
      ax.push_back(smp.accel_x_mps2);
      EXPECT_NEAR(smp.accel_x_mps2 / 0.01, std::round(smp.accel_x_mps2 / 0.01), 1e-6);
    }
    EXPECT_NEAR(test::mean(ax), kG * std::sin(grade) + s.sensors.accel_x_mps2.bias, 0.002);
  }
}

struct TurnCheck {
  double radius_m, speed_mps, yaw_rate_radps, accel_y_mps2, steering_rad;
};

TurnCheck steady_turn_means(const SimulationResult& r, double radius_m, bool left, double bias_yaw,
                            double bias_ay, double bias_sw) {
  std::vector<double> dist, v, yaw, ay, sw;
  const double cy = left ? radius_m : -radius_m;
  for (std::size_t k = 0; k < r.truth.size(); ++k) {
    if (to_seconds(r.truth[k].time_us) < 30.0) continue;
    const TruthRow& t = r.truth[k];
    dist.push_back(std::hypot(t.x_m, t.y_m - cy));
    v.push_back(std::hypot(t.speed_mps, t.lateral_velocity_mps));
    yaw.push_back(r.samples[k].yaw_rate_radps - bias_yaw);
    ay.push_back(r.samples[k].accel_y_mps2 - bias_ay);
    sw.push_back(r.samples[k].steering_wheel_angle_rad - bias_sw);
  }
  return {test::mean(dist), test::mean(v), test::mean(yaw), test::mean(ay), test::mean(sw)};
}

TEST(SimPhysics, SteadyLeftTurnMatchesVOverRAndIsoSigns) {
  // Given the steady_turn scenario: 15 m/s on a left circle of 80 m
  const Scenario s = *find_scenario("steady_turn");
  ASSERT_TRUE(s.driver.circle && s.driver.circle->left);
  const double R = s.driver.circle->radius_m;
  const SimulationResult r = run(s, ideal());
  const TurnCheck c = steady_turn_means(r, R, true, 0.0, 0.0, 0.0);
  // Then the car is on the circle, at 15 m/s, and yaw rate = v/R, a_y = v^2/R within 1 %
  EXPECT_NEAR(c.radius_m, R, 0.05);
  EXPECT_NEAR(c.speed_mps, 15.0, 0.05);
  EXPECT_NEAR(c.yaw_rate_radps, c.speed_mps / R, 0.01 * c.speed_mps / R);
  EXPECT_NEAR(c.accel_y_mps2, c.speed_mps * c.speed_mps / R, 0.01 * c.speed_mps * c.speed_mps / R);
  // And ISO 8855 signs: left turn -> positive yaw rate, a_y and steering-wheel angle
  EXPECT_GT(c.yaw_rate_radps, 0.1);
  EXPECT_GT(c.accel_y_mps2, 2.0);
  EXPECT_GT(c.steering_rad, 0.2);
  EXPECT_GT(r.truth.back().yaw_rad, 1.0);  // heading turned counter-clockwise

  // And with the real sensors (noise, bias, quantisation), after removing the documented biases
  SimulationOptions o;
  o.seed = 5;
  const SimulationResult rn = run(s, o);
  const TurnCheck n =
      steady_turn_means(rn, R, true, s.sensors.yaw_rate_radps.bias, s.sensors.accel_y_mps2.bias,
                        s.sensors.steering_wheel_angle_rad.bias);
  EXPECT_NEAR(n.yaw_rate_radps, n.speed_mps / R, 0.01 * n.speed_mps / R);
  EXPECT_NEAR(n.accel_y_mps2, n.speed_mps * n.speed_mps / R, 0.01 * n.speed_mps * n.speed_mps / R);
}

TEST(SimPhysics, SteadyRightTurnHasNegativeSigns) {
  Scenario s = *find_scenario("steady_turn");
  s.driver.circle->left = false;
  s.driver.circle->radius_m = 60.0;
  s.driver.speed_mps = PiecewiseLinear(12.0);
  s.initial_speed_mps = 12.0;
  const SimulationResult r = run(s, ideal());
  const TurnCheck c = steady_turn_means(r, 60.0, false, 0.0, 0.0, 0.0);
  EXPECT_NEAR(c.radius_m, 60.0, 0.05);
  EXPECT_NEAR(c.yaw_rate_radps, -c.speed_mps / 60.0, 0.01 * c.speed_mps / 60.0);
  EXPECT_NEAR(c.accel_y_mps2, -c.speed_mps * c.speed_mps / 60.0,
              0.01 * c.speed_mps * c.speed_mps / 60.0);
  EXPECT_LT(c.steering_rad, -0.2);
}

// Compression z where c z + k2 max(0, z - z_knee)^2 = F, by bisection (independent of the
// model's closed form).
double bisect_compression(double c, double k2, double knee, double force) {
  double lo = 0.0;
  double hi = 1.0;
  for (int i = 0; i < 200; ++i) {
    const double z = 0.5 * (lo + hi);
    const double f = c * z + k2 * std::pow(std::max(0.0, z - knee), 2);
    (f < force ? lo : hi) = z;
  }
  return 0.5 * (lo + hi);
}

TEST(SimPhysics, StaticDeflectionFollowsTheSpringCurveIncludingTheBumpStop) {
  struct Case {
    std::vector<LoadItem> items;
    bool beyond_knee;
  };
  const std::vector<Case> cases = {
      {{}, false},                                                 // empty car
      {{{80.0, 1.30, 0.37, 0.6}}, false},                          // driver only
      {{{80.0, 1.30, 0.37, 0.6}, {450.0, 2.9, -0.2, 0.7}}, true},  // heavy load behind
  };
  for (const Case& cs : cases) {
    // Given the car standing on level ground with this payload
    Scenario s = straight_scenario(0.0, 3.0);
    s.initial_payload = cs.items;
    const SimulationResult r = run(s, ideal());
    // Then the sensor reads the static compression of the spring curve under the rear-right
    // wheel load (computed here from the load items), minus the sensor reference
    double m = 1500.0, mx = 1500.0 * 1.20, my = 0.0;
    for (const LoadItem& it : cs.items) {
      m += it.mass_kg;
      mx += it.mass_kg * it.x_m;
      my += it.mass_kg * it.y_m;
    }
    const double x_cg = mx / m;
    const double y_cg = my / m;
    const double wheel_load = m * kG * (x_cg / 2.70) * (0.5 - y_cg / 1.55);
    const double spring_load = wheel_load - 40.0 * kG;
    const double z = bisect_compression(30000.0, 2.0e6, 0.126, spring_load);
    EXPECT_EQ(z > 0.126, cs.beyond_knee) << "z = " << z;
    for (const Sample& smp : r.samples) {
      EXPECT_NEAR(smp.rear_right_deflection_m, z - 0.085, 1e-7);
    }
    EXPECT_NEAR(r.truth.back().rear_right_load_n, wheel_load, 1e-6 * wheel_load);
  }
}

TEST(SimPhysics, DeflectionSettlesBackToTheStaticValueAfterDriving) {
  // Given paper_exp2, which ends standing on level ground for 16 s after 180 s of driving
  const SimulationResult r = run(*find_scenario("paper_exp2"), ideal());
  // Then the deflection is back where it started
  EXPECT_TRUE(r.truth.back().stopped);
  EXPECT_NEAR(r.truth.back().rear_right_deflection_m, r.truth.front().rear_right_deflection_m,
              2e-6);
  // And it moved a lot while driving (load transfer)
  double lo = 1.0, hi = -1.0;
  for (const TruthRow& t : r.truth) {
    lo = std::min(lo, t.rear_right_deflection_m);
    hi = std::max(hi, t.rear_right_deflection_m);
  }
  EXPECT_GT(hi - lo, 0.02);
}

TEST(SimPhysics, RotatingMassTakesItsShareOfTheWheelForce) {
  // Given the launch of paper_exp1 in first gear on level ground (5.5 .. 8.5 s)
  const SimulationResult r = run(*find_scenario("paper_exp1"), ideal());
  const double M = 1659.0;
  double dv_with = 0.0;
  double dv_without = 0.0;
  std::size_t k0 = 550, k1 = 850;
  auto accel = [&](std::size_t k, bool with_rot) {
    const TruthRow& t = r.truth[k];
    const double f = t.wheel_torque_nm / 0.31 - t.brake_force_n - t.drag_force_n -
                     t.rolling_resistance_n - M * kG * std::sin(t.grade_rad);
    return f / (M + (with_rot ? t.rotating_mass_kg : 0.0));
  };
  for (std::size_t k = k0; k < k1; ++k) {
    ASSERT_EQ(r.truth[k].gear, 1);
    ASSERT_FALSE(r.truth[k].stopped);
    dv_with += 0.5 * (accel(k, true) + accel(k + 1, true)) * 0.01;
    dv_without += 0.5 * (accel(k, false) + accel(k + 1, false)) * 0.01;
  }
  // Then (M + m_rot) dv/dt = T/r - resistances integrates to the speed gained
  const double dv = r.truth[k1].speed_mps - r.truth[k0].speed_mps;
  ASSERT_GT(dv, 2.0);
  EXPECT_NEAR(dv_with, dv, 0.003 * dv);
  // And ignoring m_rot (11 % of M in first gear) would be clearly wrong
  EXPECT_GT(dv_without - dv, 0.08 * dv);
  EXPECT_NEAR(r.truth[k0].rotating_mass_kg,
              (3.6 + 0.92 * 0.08 * std::pow(3.5 * 4.0, 2)) / (0.31 * 0.31), 1e-9);
}

TEST(SimPhysics, GearShiftsOpenTheClutchForAboutATenthOfASecond) {
  const SimulationResult r = run(*find_scenario("paper_exp2"), ideal());
  int shifts = 0;
  int open_ticks = 0;
  for (std::size_t k = 1; k < r.truth.size(); ++k) {
    if (r.truth[k].gear == 0) {
      ++open_ticks;
      EXPECT_EQ(r.truth[k].wheel_torque_nm, 0.0);
      EXPECT_NEAR(r.truth[k].rotating_mass_kg, 3.6 / (0.31 * 0.31), 1e-9);
      if (r.truth[k - 1].gear != 0) ++shifts;
    }
  }
  EXPECT_GE(shifts, 6);
  EXPECT_NEAR(static_cast<double>(open_ticks) / shifts, 10.0, 1.01);
}

}  // namespace
}  // namespace vmass::sim

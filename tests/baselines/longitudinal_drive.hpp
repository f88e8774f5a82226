// A small longitudinal simulator for the baseline tests: a point-mass car on a road with a grade
// profile, aero drag, rolling resistance, rotating parts, brakes and an optional stepped gearbox,
// driven along a speed profile by a proportional driver; its sensors read at the tick rate with
// seeded Gaussian noise. Self-contained so the tests do not depend on the product simulator.
//
//   (M + m_rot) dv/dt = T / r - K P - 1/2 rho C_d A v^2 - M g (f_r cos(beta) + sin(beta))
//   a_x = dv/dt + g sin(beta)                           (accelerometer: specific force)
// At every tick the sampled torque, pressure, speed and a_x satisfy this relation exactly (before
// noise): a_x is the instantaneous derivative, not a difference. Integration: explicit Euler at
// steps_per_tick times the tick rate. Pure function of its spec; thread-safe.
#pragma once

#include <cstdint>
#include <vector>

#include "vmass/baselines/nominal_vehicle.hpp"
#include "vmass/core/sample.hpp"

namespace vmass::baselines::testing {

/// y(x) linear between breakpoints (non-decreasing x), held outside them.
struct Breakpoint {
  double x = 0.0;
  double y = 0.0;
};
double interpolate(const std::vector<Breakpoint>& points, double x);

struct DriveCar {
  double mass_kg = 1659.0;
  double rotating_mass_kg = 0.0;
  double wheel_radius_m = 0.31;
  double brake_gain_n_per_pa = 0.0033;
  double drag_area_m2 = 0.75;
  double air_density_kg_per_m3 = 1.2;
  double rolling_resistance_coeff = 0.011;
  double gravity_mps2 = 9.80665;
  double max_power_w = 110e3;
  double max_drive_force_n = 7000.0;
  std::vector<double> max_force_by_gear_n;  ///< full-throttle wheel force per gear; empty: above
  double force_lag_s = 0.1;                 ///< engine and brake response
  double min_brake_pressure_pa = 3.0e4;     ///< drivers brake with at least this, or coast
  std::vector<double> upshift_speeds_mps;   ///< gear g + 1 above entry g - 1; empty: one gear
  double shift_time_s = 0.0;                ///< torque cut while shifting (gear reads 0)
};

struct DriveSensors {  ///< white Gaussian noise std per tick
  double accel_x_std_mps2 = 0.0;
  double accel_y_std_mps2 = 0.0;
  double speed_std_mps = 0.0;
  double torque_std_nm = 0.0;
  double brake_std_pa = 0.0;
  bool has_brake_pressure = true;
  bool has_gear = false;
};

struct DriveSpec {
  DriveCar car;
  DriveSensors sensors;
  std::vector<Breakpoint> speed_profile_mps;  ///< over time, s
  std::vector<Breakpoint> grade_profile_rad;  ///< over distance, m
  double duration_s = 60.0;
  double tick_rate_hz = 100.0;
  int steps_per_tick = 10;
  double speed_gain_per_s = 1.5;  ///< driver: extra acceleration per m/s of speed error
  std::uint64_t seed = 1;
};

struct DriveLog {
  std::vector<vmass::Sample> samples;
  std::vector<double> grade_rad;  ///< true grade per tick
};

DriveLog simulate_drive(const DriveSpec& spec);

/// The datasheet of the simulated car: exact (the tests check the methods, not calibration),
/// with the empty mass the car is driven without its load.
NominalVehicle nominal_of(const DriveCar& car, double empty_mass_kg);

}  // namespace vmass::baselines::testing

// The drives "like each baseline's own paper", built from longitudinal_drive.hpp. Each says what
// it reproduces and why the assertion on it is fair.
#pragma once

#include <cmath>
#include <vector>

#include "longitudinal_drive.hpp"

namespace vmass::baselines::testing {

inline double grade_from_percent(double percent) { return std::atan(percent / 100.0); }

/// El Mrhasli et al., Experiment 1: a segment of a European urban cycle (one ECE-15 elementary
/// cycle, 195 s) on a straight road with a slope profile, 1659 kg, a clean simulation (no added
/// noise, no rotating inertia: the paper's model has none and it reports 0.38 % on this case).
inline DriveSpec paper_experiment1_drive() {
  DriveSpec spec;
  spec.car.mass_kg = 1659.0;
  constexpr double kKmh = 1.0 / 3.6;
  spec.speed_profile_mps = {{0, 0},           {11, 0},          {15, 15 * kKmh},  {23, 15 * kKmh},
                            {28, 0},          {49, 0},          {61, 32 * kKmh},  {85, 32 * kKmh},
                            {96, 0},          {117, 0},         {143, 50 * kKmh}, {155, 50 * kKmh},
                            {163, 35 * kKmh}, {176, 35 * kKmh}, {188, 0},         {195, 0}};
  spec.grade_profile_rad = {{0, 0.0},
                            {60, 0.0},
                            {120, grade_from_percent(5.0)},
                            {300, grade_from_percent(5.0)},
                            {420, grade_from_percent(-3.0)},
                            {600, grade_from_percent(-3.0)},
                            {700, 0.0}};
  spec.duration_s = 195.0;
  return spec;
}

/// Vahidi et al.: a loaded heavy truck (25 t, tractor-semitrailer class) at full throttle through
/// its gears (the wheel force steps down at every upshift, with a torque cut while shifting), then
/// in traffic with frequent speed changes over a 3 % climb, a 2 % descent and a 1 % climb; speed
/// from the wheels (noisy), no accelerometer used; drag and rolling coefficients known exactly.
inline DriveSpec vahidi_truck_drive() {
  DriveSpec spec;
  DriveCar& car = spec.car;
  car.mass_kg = 25000.0;
  car.rotating_mass_kg = 1000.0;
  car.wheel_radius_m = 0.5;
  car.brake_gain_n_per_pa = 0.18;
  car.drag_area_m2 = 6.0;
  car.rolling_resistance_coeff = 0.006;
  car.max_power_w = 300e3;
  car.max_drive_force_n = 50e3;
  // Full throttle: the wheel force steps down with the gear ratio at every upshift.
  car.max_force_by_gear_n = {50e3, 42e3, 35e3, 29e3, 24e3, 20e3, 17e3, 14.5e3, 12.5e3};
  car.force_lag_s = 0.2;
  car.upshift_speeds_mps = {2.5, 4.0, 6.0, 8.5, 11.0, 14.0, 17.5, 21.0};
  car.shift_time_s = 0.8;
  spec.sensors.speed_std_mps = 0.02;
  spec.sensors.torque_std_nm = 100.0;
  spec.sensors.brake_std_pa = 3000.0;
  spec.sensors.has_gear = true;
  // From a stop through the gears to 15 m/s, then a driver in traffic: a new target speed every
  // 10 s, alternately faster and slower (torque steps of about 10 kN), 15 to 24 m/s.
  spec.speed_profile_mps = {{0, 0}, {5, 0}, {35, 15}, {60, 15}};
  const double targets[] = {18, 16, 20, 17, 22, 19, 24, 20, 23, 18};
  for (int i = 0; i < 44; ++i) spec.speed_profile_mps.push_back({70.0 + 10.0 * i, targets[i % 10]});
  spec.grade_profile_rad = {{0, 0.0},
                            {300, 0.0},
                            {600, grade_from_percent(3.0)},
                            {2000, grade_from_percent(3.0)},
                            {2500, grade_from_percent(-2.0)},
                            {4000, grade_from_percent(-2.0)},
                            {4500, grade_from_percent(1.0)}};
  spec.duration_s = 500.0;
  spec.speed_gain_per_s = 0.8;
  return spec;
}

/// Fathy et al.: a loaded SUV (2 t) driven hard: repeated strong accelerations through the gears
/// (torque cuts at the shifts) and hard braking, over rolling grades of up to 4 %, with the
/// accelerometer, torque, speed and brake-pressure noise of production sensors.
inline DriveSpec fathy_car_drive() {
  DriveSpec spec;
  DriveCar& car = spec.car;
  car.mass_kg = 2000.0;
  car.rotating_mass_kg = 60.0;
  car.wheel_radius_m = 0.35;
  car.brake_gain_n_per_pa = 0.004;
  car.drag_area_m2 = 0.9;
  car.rolling_resistance_coeff = 0.012;
  car.max_power_w = 150e3;
  car.max_drive_force_n = 8000.0;
  car.force_lag_s = 0.12;
  car.upshift_speeds_mps = {7.0, 13.0, 19.0, 25.0};
  car.shift_time_s = 0.4;
  spec.sensors.accel_x_std_mps2 = 0.02;
  spec.sensors.accel_y_std_mps2 = 0.02;
  spec.sensors.speed_std_mps = 0.02;
  spec.sensors.torque_std_nm = 20.0;
  spec.sensors.brake_std_pa = 3000.0;
  spec.sensors.has_gear = true;
  double t = 0.0;
  for (int lap = 0; lap < 6; ++lap) {  // 0 -> 20 -> 5 -> 25 -> 0 m/s, about 33 s a lap
    spec.speed_profile_mps.push_back({t, 0.0});
    spec.speed_profile_mps.push_back({t + 2.0, 0.0});
    spec.speed_profile_mps.push_back({t + 10.0, 20.0});
    spec.speed_profile_mps.push_back({t + 15.0, 20.0});
    spec.speed_profile_mps.push_back({t + 18.75, 5.0});
    spec.speed_profile_mps.push_back({t + 26.75, 25.0});
    spec.speed_profile_mps.push_back({t + 33.0, 0.0});
    t += 33.0;
  }
  for (int i = 0; i < 40; ++i) {  // grades alternating over 150 m stretches
    const double percent = (i % 4 == 0) ? 0.0 : (i % 4 == 1 ? 4.0 : (i % 4 == 2 ? 1.0 : -3.0));
    spec.grade_profile_rad.push_back({150.0 * i, grade_from_percent(percent)});
  }
  spec.duration_s = t;
  return spec;
}

}  // namespace vmass::baselines::testing

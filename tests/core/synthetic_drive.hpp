// Test helper: synthetic drives with known answers, independent of the estimator code.
//
// Longitudinal: a point mass M with rotating mass m_rot on a road with grade, aero drag and
// rolling resistance; the wheel force is whatever makes dv/dt follow the requested profile; the
// accelerometer reads the specific force dv/dt + g sin(grade).
// Lateral: the linear single-track model integrated with small steps, ISO 8855 signs.
#pragma once

#include <cmath>
#include <functional>
#include <random>
#include <vector>

#include "vmass/core/sample.hpp"
#include "vmass/core/vehicle_params.hpp"

namespace vmass::testing {

inline VehicleParams test_vehicle() {
  VehicleParams v;
  v.empty_mass_kg = 1500.0;
  v.wheelbase_m = 2.7;
  v.cg_to_front_axle_m = 1.2;
  v.wheel_radius_m = 0.31;
  v.brake_gain_n_per_pa = 3e-4;  // N per Pa: 100 bar -> 3000 N
  v.steering_ratio = 15.0;
  v.cornering_stiffness_front_n_per_rad = 1.5e5;
  v.cornering_stiffness_rear_n_per_rad = 1.7e5;
  v.rotating_mass_kg = 40.0;
  v.pitch_gradient_deg_per_g = 0.0;  // the synthetic accelerometer does not pitch
  return v;
}

inline SuspensionParams test_suspension() {
  SuspensionParams s;
  s.stiffness_n_per_m = 30000.0;
  s.empty_deflection_m = 0.010;
  return s;
}

/// The sample as a bus without wheel torque reports it, in `gear`: the engine torque behind its
/// wheel torque through the overall ratio, the driveline efficiency and a converter's torque
/// ratio, and the engine speed the wheels give through the ratio times engine_speed_factor (a
/// slipping clutch or converter turns the engine faster).
inline void report_engine_torque(Sample* s, const VehicleParams& v, int gear, double overall_ratio,
                                 double efficiency, double torque_ratio = 1.0,
                                 double engine_speed_factor = 1.0) {
  const double wheel_nm = s->wheel_torque_nm;
  const double losses = wheel_nm >= 0.0 ? efficiency : 1.0 / efficiency;
  s->valid &= ~input_bit(Input::kWheelTorque);
  s->set(Input::kEngineTorque, wheel_nm / (torque_ratio * overall_ratio * losses));
  s->set(Input::kGear, static_cast<double>(gear));
  s->set(Input::kEngineSpeed,
         s->speed_mps / v.wheel_radius_m * overall_ratio * engine_speed_factor);
}

inline double deflection_for(double mass_kg, const VehicleParams& v, const SuspensionParams& s) {
  return s.empty_deflection_m + (mass_kg - v.empty_mass_kg) * v.cg_to_front_axle_m *
                                    v.gravity_mps2 / (2.0 * v.wheelbase_m * s.stiffness_n_per_m);
}

struct LongitudinalDrive {
  double mass_kg = 1650.0;
  double rotating_mass_kg = 40.0;
  double drag_coefficient_kg_per_m = 0.4;  // 0.5 rho Cd A
  double rolling_resistance_n = 180.0;
  std::function<double(double)> grade_rad = [](double t) { return 0.03 * std::sin(0.05 * t); };
  std::function<double(double)> accel_mps2 = [](double t) {
    return 0.8 * std::sin(0.6 * t) + 0.4 * std::sin(1.7 * t);
  };
  double accel_noise_std_mps2 = 0.0;
  double force_noise_std_n = 0.0;
  unsigned seed = 1;
};

/// Samples at 100 Hz from t0 to t1 while driving (speed starts at v0, never below 2 m/s).
inline std::vector<Sample> longitudinal_samples(const LongitudinalDrive& d, const VehicleParams& v,
                                                double t0_s, double t1_s, double v0_mps,
                                                double deflection_m) {
  std::vector<Sample> out;
  std::mt19937_64 rng(d.seed);
  std::normal_distribution<double> accel_noise(
      0.0, d.accel_noise_std_mps2 > 0 ? d.accel_noise_std_mps2 : 1.0);
  std::normal_distribution<double> force_noise(0.0,
                                               d.force_noise_std_n > 0 ? d.force_noise_std_n : 1.0);
  double speed = v0_mps;
  const double dt = 0.01;
  for (double t = t0_s; t < t1_s - 1e-9; t += dt) {
    const double a = d.accel_mps2(t);
    const double grade = d.grade_rad(t);
    const double resist = d.drag_coefficient_kg_per_m * speed * speed + d.rolling_resistance_n +
                          d.mass_kg * v.gravity_mps2 * std::sin(grade);
    const double wheel_force = (d.mass_kg + d.rotating_mass_kg) * a + resist;
    Sample s;
    s.time_us = from_seconds(t);
    // Positive force from the powertrain, negative from the brakes.
    const double fn = d.force_noise_std_n > 0 ? force_noise(rng) : 0.0;
    if (wheel_force >= 0) {
      s.set(Input::kWheelTorque, (wheel_force + fn) * v.wheel_radius_m);
      s.set(Input::kBrakePressure, 0.0);
    } else {
      s.set(Input::kWheelTorque, fn * v.wheel_radius_m);
      s.set(Input::kBrakePressure, -wheel_force / v.brake_gain_n_per_pa);
    }
    const double an = d.accel_noise_std_mps2 > 0 ? accel_noise(rng) : 0.0;
    s.set(Input::kAccelX, a + v.gravity_mps2 * std::sin(grade) + an);
    s.set(Input::kAccelY, 0.0);
    s.set(Input::kYawRate, 0.0);
    s.set(Input::kSpeed, speed);
    s.set(Input::kSteeringWheelAngle, 0.0);
    s.set(Input::kRearRightDeflection, deflection_m);
    out.push_back(s);
    speed = std::max(2.0, speed + a * dt);
  }
  return out;
}

/// Standing still with the given deflection, 100 Hz.
inline std::vector<Sample> standstill_samples(double t0_s, double t1_s, double deflection_m) {
  std::vector<Sample> out;
  for (double t = t0_s; t < t1_s - 1e-9; t += 0.01) {
    Sample s;
    s.time_us = from_seconds(t);
    s.set(Input::kWheelTorque, 0.0);
    s.set(Input::kBrakePressure, 2e6);
    s.set(Input::kAccelX, 0.0);
    s.set(Input::kAccelY, 0.0);
    s.set(Input::kYawRate, 0.0);
    s.set(Input::kSpeed, 0.0);
    s.set(Input::kSteeringWheelAngle, 0.0);
    s.set(Input::kRearRightDeflection, deflection_m);
    out.push_back(s);
  }
  return out;
}

struct BicycleDrive {
  double mass_kg = 1650.0;
  double yaw_inertia_kgm2 = 2600.0;
  double speed_mps = 15.0;
  std::function<double(double)> steering_wheel_rad = [](double t) {
    return 0.7 * std::sin(2.0 * 3.14159265358979 * 0.4 * t);
  };
};

/// The linear single-track model (the estimator's own assumptions: known C_alpha), constant
/// speed, integrated at 1 kHz and sampled at 100 Hz. Signs: ISO 8855.
inline std::vector<Sample> bicycle_samples(const BicycleDrive& d, const VehicleParams& v,
                                           double t0_s, double t1_s, double deflection_m) {
  std::vector<Sample> out;
  const double vx = d.speed_mps, lf = v.cg_to_front_axle_m, lr = v.cg_to_rear_axle_m();
  // Right-hand side of the model: returns (a_y, dv_y/dt, dr/dt) for a state and time.
  struct Rates {
    double ay, vy_dot, r_dot;
  };
  auto rates = [&](double t, double vy, double r) {
    const double delta = d.steering_wheel_rad(t) / v.steering_ratio;
    const double af = delta - std::atan(vy / vx) - lf * r / vx;
    const double ar = -std::atan(vy / vx) + lr * r / vx;
    const double fyf = v.cornering_stiffness_front_n_per_rad * af;
    const double fyr = v.cornering_stiffness_rear_n_per_rad * ar;
    const double ay = (fyf * std::cos(delta) + fyr) / d.mass_kg;  // specific force
    return Rates{ay, ay - r * vx, (lf * fyf * std::cos(delta) - lr * fyr) / d.yaw_inertia_kgm2};
  };
  double vy = 0.0, r = 0.0;
  const double h = 0.001;
  int k = 0;
  for (double t = t0_s; t < t1_s - 1e-9; t += h, ++k) {
    const Rates now = rates(t, vy, r);
    if (k % 10 == 0) {
      Sample s;
      s.time_us = from_seconds(t);
      s.set(Input::kWheelTorque, 0.0);
      s.set(Input::kBrakePressure, 0.0);
      s.set(Input::kAccelX, -r * vy);  // dv_x/dt = 0 = a_x + r v_y
      s.set(Input::kAccelY, now.ay);
      s.set(Input::kYawRate, r);
      s.set(Input::kSpeed, vx);
      s.set(Input::kSteeringWheelAngle, d.steering_wheel_rad(t));
      s.set(Input::kRearRightDeflection, deflection_m);
      out.push_back(s);
    }
    // Classic RK4, so that the test data is far more accurate than the estimator needs.
    const Rates k2 = rates(t + h / 2, vy + h / 2 * now.vy_dot, r + h / 2 * now.r_dot);
    const Rates k3 = rates(t + h / 2, vy + h / 2 * k2.vy_dot, r + h / 2 * k2.r_dot);
    const Rates k4 = rates(t + h, vy + h * k3.vy_dot, r + h * k3.r_dot);
    vy += h / 6 * (now.vy_dot + 2 * k2.vy_dot + 2 * k3.vy_dot + k4.vy_dot);
    r += h / 6 * (now.r_dot + 2 * k2.r_dot + 2 * k3.r_dot + k4.r_dot);
  }
  return out;
}

}  // namespace vmass::testing

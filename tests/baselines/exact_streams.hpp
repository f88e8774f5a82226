// Streams of ticks on which a baseline's regression holds exactly, generated in the test: the
// known answer is the mass they were made with.
#pragma once

#include <cmath>
#include <vector>

#include "vmass/baselines/nominal_vehicle.hpp"
#include "vmass/core/sample.hpp"

namespace vmass::baselines::testing {

constexpr double kTwoPi = 6.283185307179586;

/// Accelerometer reading of the exact streams: two tones in the band every method uses.
inline double exact_accel_mps2(double t_s) {
  return 0.8 * std::sin(kTwoPi * 0.3 * t_s) + 0.5 * std::sin(kTwoPi * 0.9 * t_s + 1.0);
}

/// The wheel force F = C / r - K P split into torque (F >= 0) or brake pressure (F < 0).
inline void set_wheel_force(double force_n, const NominalVehicle& car, vmass::Sample* s) {
  s->set(vmass::Input::kWheelTorque, force_n > 0.0 ? force_n * car.wheel_radius_m : 0.0);
  s->set(vmass::Input::kBrakePressure, force_n < 0.0 ? -force_n / car.brake_gain_n_per_pa : 0.0);
}

/// Braking made unmistakable: at least 1 bar whenever the brakes are on (the force is then no
/// longer K P; for methods that must leave braking out).
inline void press_brakes_firmly(std::vector<vmass::Sample>* samples) {
  for (auto& s : *samples) {
    if (s.brake_pressure_pa > 0.0) s.brake_pressure_pa += 1.0e5;
  }
}

/// Ticks at rate_hz from t0_s on which F = C / r - K P = M a_x + offset_n exactly, a_y = 0,
/// rolling at 15 m/s, every input valid.
inline std::vector<vmass::Sample> exact_force_stream(const NominalVehicle& car, double mass_kg,
                                                     double offset_n, double t0_s,
                                                     double duration_s, double rate_hz = 100.0) {
  std::vector<vmass::Sample> out;
  const long n = std::lround(duration_s * rate_hz);
  for (long k = 0; k < n; ++k) {
    const double t = t0_s + static_cast<double>(k) / rate_hz;
    vmass::Sample s;
    s.time_us = vmass::from_seconds(t);
    const double accel = exact_accel_mps2(t);
    set_wheel_force(mass_kg * accel + offset_n, car, &s);
    s.set(vmass::Input::kAccelX, accel);
    s.set(vmass::Input::kAccelY, 0.0);
    s.set(vmass::Input::kSpeed, 15.0);
    out.push_back(s);
  }
  return out;
}

}  // namespace vmass::baselines::testing

namespace vmass::baselines::testing {

/// A car for the exact streams (no drag: the drag of a sampled speed is not exact between ticks).
inline NominalVehicle exact_car(double empty_mass_kg, double rotating_mass_kg = 0.0) {
  NominalVehicle car;
  car.empty_mass_kg = empty_mass_kg;
  car.wheel_radius_m = 0.3;
  car.brake_gain_n_per_pa = 0.004;
  car.rotating_mass_kg = rotating_mass_kg;
  car.drag_area_m2 = 0.0;
  car.rolling_resistance_coeff = 0.01;
  return car;
}

/// Ticks on which Vahidi's regression holds exactly: the traction force is linear between ticks,
/// so dv/dt is too and the wheel speed, integrated by the trapezoidal rule, gives
/// (v_k - v_{k-1}) f = (a_{k-1} + a_k) / 2 with (M + m_rot) a = F - M g (f_r cos b + sin b).
/// The force averages to the grade and rolling load, so the speed stays near 15 m/s.
inline std::vector<vmass::Sample> exact_speed_stream(const NominalVehicle& car, double mass_kg,
                                                     double grade_rad, double duration_s,
                                                     double rate_hz = 100.0) {
  const double load_n = mass_kg * car.gravity_mps2 *
                        (car.rolling_resistance_coeff * std::cos(grade_rad) + std::sin(grade_rad));
  std::vector<vmass::Sample> out;
  double speed = 15.0, previous_accel = 0.0;
  const long n = std::lround(duration_s * rate_hz);
  for (long k = 0; k < n; ++k) {
    const double t = static_cast<double>(k) / rate_hz;
    const double force =
        load_n + 2000.0 * std::sin(kTwoPi * 0.25 * t) + 1200.0 * std::sin(kTwoPi * 0.7 * t);
    const double accel = (force - load_n) / (mass_kg + car.rotating_mass_kg);
    if (k > 0) speed += 0.5 * (previous_accel + accel) / rate_hz;
    previous_accel = accel;
    vmass::Sample s;
    s.time_us = vmass::from_seconds(t);
    s.set(vmass::Input::kWheelTorque, force * car.wheel_radius_m);  // < 0: engine braking
    s.set(vmass::Input::kBrakePressure, 0.0);
    s.set(vmass::Input::kAccelX, accel + car.gravity_mps2 * std::sin(grade_rad));
    s.set(vmass::Input::kAccelY, 0.0);
    s.set(vmass::Input::kSpeed, speed);
    out.push_back(s);
  }
  return out;
}

}  // namespace vmass::baselines::testing

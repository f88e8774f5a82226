// A small deterministic drive for the service tests (given the mass, the samples a car would
// produce): standstill, a speed-up, sinusoidal acceleration cycles at 5-6.5 m/s (longitudinal
// events of Table II), standstill again. The wheel torque obeys F = (M + m_rot) a + F_resist with
// seeded noise; the rear-right deflection is eq. (3) solved for z at mass M.
#pragma once

#include <cmath>
#include <cstdio>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include "vmass/core/sample.hpp"
#include "vmass/csv/samples_csv.hpp"

namespace vmass::test {

struct DriveSpec {
  double mass_kg = 1800.0;
  double duration_s = 60.0;   ///< total, including both standstills
  double standstill_s = 5.0;  ///< at the start and at the end
  double tick_rate_hz = 100.0;
  unsigned seed = 7;
  // Must match test_config_yaml():
  double empty_mass_kg = 1500.0, wheelbase_m = 2.7, cg_to_front_axle_m = 1.2, wheel_radius_m = 0.31,
         stiffness_n_per_m = 30000.0, gravity_mps2 = 9.80665;
};

inline double deflection_for_mass(const DriveSpec& d, double mass_kg) {
  // eq. (3): M = M_idle + 2 l c z / (l_f g)  =>  z = (M - M_idle) l_f g / (2 l c), z0 = 0
  return (mass_kg - d.empty_mass_kg) * d.cg_to_front_axle_m * d.gravity_mps2 /
         (2.0 * d.wheelbase_m * d.stiffness_n_per_m);
}

inline std::vector<Sample> make_drive(const DriveSpec& d) {
  std::mt19937 rng(d.seed);
  std::normal_distribution<double> torque_noise(0.0, 15.0);  // N*m
  std::normal_distribution<double> accel_noise(0.0, 0.005);  // m/s^2
  const int n = static_cast<int>(std::lround(d.duration_s * d.tick_rate_hz)) + 1;
  const double dt = 1.0 / d.tick_rate_hz;
  const double resist_n = 120.0;
  std::vector<Sample> out;
  out.reserve(static_cast<std::size_t>(n));
  double speed = 0.0;
  for (int i = 0; i < n; ++i) {
    const double t = i * dt;
    double a = 0.0;
    const double drive_start = d.standstill_s, drive_end = d.duration_s - d.standstill_s;
    if (t >= drive_start && t < drive_start + 5.0) {
      a = 1.0;
    } else if (t >= drive_start + 5.0 && t < drive_end - 6.0) {
      a = 0.8 * std::sin(2.0 * M_PI * (t - drive_start - 5.0) / 6.0);
    } else if (t >= drive_end - 6.0 && t < drive_end) {
      a = -speed / std::max(drive_end - t, dt);  // come to rest at drive_end
    }
    const bool moving = t >= drive_start && t < drive_end;
    Sample s;
    s.time_us = from_seconds(t);
    s.set(Input::kWheelTorque,
          moving ? (d.mass_kg * a + resist_n) * d.wheel_radius_m + torque_noise(rng) : 0.0);
    s.set(Input::kBrakePressure, 0.0);
    s.set(Input::kAccelX, a + accel_noise(rng));
    s.set(Input::kAccelY, accel_noise(rng));
    s.set(Input::kYawRate, 0.0);
    s.set(Input::kSpeed, speed);
    s.set(Input::kSteeringWheelAngle, 0.0);
    s.set(Input::kRearRightDeflection, deflection_for_mass(d, d.mass_kg));
    s.set(Input::kGear, 2.0);
    out.push_back(s);
    speed = moving ? std::max(0.0, speed + a * dt) : 0.0;
  }
  return out;
}

inline bool write_samples_csv(const std::string& path, const std::vector<Sample>& samples) {
  std::ofstream out(path);
  out << "time_s";
  for (int i = 0; i < kInputCount; ++i) out << "," << samples_csv_column(static_cast<Input>(i));
  out << "\n";
  char buf[64];
  for (const Sample& s : samples) {
    std::snprintf(buf, sizeof buf, "%.6f", to_seconds(s.time_us));
    out << buf;
    for (int i = 0; i < kInputCount; ++i) {
      const auto in = static_cast<Input>(i);
      out << ",";
      if (!s.has(in)) continue;
      std::snprintf(buf, sizeof buf, "%.17g", s.value(in));
      out << buf;
    }
    out << "\n";
  }
  return static_cast<bool>(out);
}

/// A config matching DriveSpec's defaults; `extra` is appended (lcm:, daemon: sections).
inline std::string test_config_yaml(const std::string& extra = "",
                                    const std::string& type = "bayes") {
  return "vehicle:\n"
         "  empty_mass_kg: 1500.0\n"
         "  wheelbase_m: 2.7\n"
         "  cg_to_front_axle_m: 1.2\n"
         "  wheel_radius_m: 0.31\n"
         "  brake_gain_n_per_pa: 0.0033\n"
         "  steering_ratio: 15.5\n"
         "  cornering_stiffness_front_n_per_rad: 150000.0\n"
         "  cornering_stiffness_rear_n_per_rad: 170000.0\n"
         "suspension:\n"
         "  stiffness_n_per_m: 30000.0\n"
         "estimator:\n"
         "  type: " +
         type +
         "\n"
         "  tick_rate_hz: 100.0\n"
         "  differencing_dt_s: 0.1\n"
         "  bayes:\n"
         "    batch_size: 50\n" +
         extra;
}

inline bool write_text(const std::string& path, const std::string& text) {
  std::ofstream out(path);
  out << text;
  return static_cast<bool>(out);
}

}  // namespace vmass::test

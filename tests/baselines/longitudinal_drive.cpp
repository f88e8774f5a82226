#include "longitudinal_drive.hpp"

#include <algorithm>
#include <cmath>
#include <random>

namespace vmass::baselines::testing {

double interpolate(const std::vector<Breakpoint>& points, double x) {
  if (points.empty()) return 0.0;
  if (x <= points.front().x) return points.front().y;
  for (std::size_t i = 1; i < points.size(); ++i) {
    if (x < points[i].x) {
      const Breakpoint& a = points[i - 1];
      const Breakpoint& b = points[i];
      return a.y + (b.y - a.y) * (x - a.x) / (b.x - a.x);
    }
  }
  return points.back().y;
}

namespace {

struct State {
  double speed_mps = 0.0;
  double distance_m = 0.0;
  double force_n = 0.0;  ///< lagged wheel force command: > 0 traction, < 0 braking
  int gear = 1;
  double shift_left_s = 0.0;
};

struct Forces {
  double traction_n = 0.0;
  double brake_n = 0.0;
  double accel_mps2 = 0.0;  ///< dv/dt
  double grade_rad = 0.0;
};

double resistance_n(const DriveCar& car, double speed_mps, double grade_rad) {
  const double drag = 0.5 * car.air_density_kg_per_m3 * car.drag_area_m2 * speed_mps * speed_mps;
  const double rolling = car.rolling_resistance_coeff * std::cos(grade_rad);
  return drag + car.mass_kg * car.gravity_mps2 * (rolling + std::sin(grade_rad));
}

double driver_command_n(const DriveSpec& spec, const State& s, double t, double grade_rad) {
  const DriveCar& car = spec.car;
  constexpr double kLookS = 0.05;
  const double v_ref = interpolate(spec.speed_profile_mps, t);
  const double dv_ref = (interpolate(spec.speed_profile_mps, t + kLookS) - v_ref) / kLookS;
  const double accel = dv_ref + spec.speed_gain_per_s * (v_ref - s.speed_mps);
  const double wanted =
      (car.mass_kg + car.rotating_mass_kg) * accel + resistance_n(car, s.speed_mps, grade_rad);
  if (v_ref <= 0.0 && s.speed_mps < 0.05) return -car.mass_kg * 3.0;  // hold at a stop
  if (wanted <= 0.0) {
    const double lightest_brake_n = car.brake_gain_n_per_pa * car.min_brake_pressure_pa;
    return wanted > -lightest_brake_n ? 0.0 : wanted;  // coast rather than brake lightly
  }
  const double power_limit = car.max_power_w / std::max(s.speed_mps, 1.0);
  const auto& by_gear = car.max_force_by_gear_n;
  const std::size_t gear = static_cast<std::size_t>(s.gear);
  const double gear_limit =
      gear >= 1 && gear <= by_gear.size() ? by_gear[gear - 1] : car.max_drive_force_n;
  return std::min({wanted, gear_limit, power_limit});
}

Forces forces_at(const DriveCar& car, const State& s, double grade_rad) {
  Forces f;
  f.grade_rad = grade_rad;
  f.traction_n = s.shift_left_s > 0.0 ? 0.0 : std::max(s.force_n, 0.0);
  f.brake_n = std::max(-s.force_n, 0.0);
  const double resist = resistance_n(car, s.speed_mps, f.grade_rad);
  const double net = f.traction_n - resist;
  if (s.speed_mps <= 0.0 && net <= f.brake_n) return f;  // standing: held by brakes or friction
  f.accel_mps2 = (net - f.brake_n) / (car.mass_kg + car.rotating_mass_kg);
  return f;
}

void update_gear(const DriveCar& car, double dt_s, State* s) {
  if (s->shift_left_s > 0.0) {
    s->shift_left_s -= dt_s;
    if (s->shift_left_s <= 0.0) ++s->gear;
    return;
  }
  const auto& up = car.upshift_speeds_mps;
  const std::size_t g = static_cast<std::size_t>(s->gear);
  if (g <= up.size() && s->speed_mps > up[g - 1]) s->shift_left_s = car.shift_time_s;
  if (g >= 2 && s->speed_mps < 0.8 * up[g - 2]) --s->gear;  // downshift: no torque cut
}

vmass::Sample read_sensors(const DriveSpec& spec, const State& s, const Forces& f, double t,
                           std::mt19937_64& rng) {
  std::normal_distribution<double> unit(0.0, 1.0);
  const DriveCar& car = spec.car;
  const DriveSensors& n = spec.sensors;
  vmass::Sample out;
  out.time_us = vmass::from_seconds(t);
  out.set(vmass::Input::kWheelTorque,
          f.traction_n * car.wheel_radius_m + n.torque_std_nm * unit(rng));
  const double pressure = f.brake_n / car.brake_gain_n_per_pa;
  const double pressure_noise = n.brake_std_pa * unit(rng);
  if (n.has_brake_pressure) out.set(vmass::Input::kBrakePressure, pressure + pressure_noise);
  const double specific = f.accel_mps2 + car.gravity_mps2 * std::sin(f.grade_rad);
  out.set(vmass::Input::kAccelX, specific + n.accel_x_std_mps2 * unit(rng));
  out.set(vmass::Input::kAccelY, n.accel_y_std_mps2 * unit(rng));
  out.set(vmass::Input::kYawRate, 0.0);
  out.set(vmass::Input::kSpeed, s.speed_mps + n.speed_std_mps * unit(rng));
  out.set(vmass::Input::kSteeringWheelAngle, 0.0);
  if (n.has_gear) out.set(vmass::Input::kGear, s.shift_left_s > 0.0 ? 0.0 : s.gear);
  return out;
}

}  // namespace

DriveLog simulate_drive(const DriveSpec& spec) {
  DriveLog log;
  std::mt19937_64 rng(spec.seed);
  const double dt_s = 1.0 / (spec.tick_rate_hz * spec.steps_per_tick);
  const long ticks = std::lround(spec.duration_s * spec.tick_rate_hz);
  State s;
  s.speed_mps = interpolate(spec.speed_profile_mps, 0.0);
  for (long k = 0; k <= ticks; ++k) {
    for (int i = 0; i < spec.steps_per_tick; ++i) {
      const double t = (static_cast<double>(k) + static_cast<double>(i) / spec.steps_per_tick) /
                       spec.tick_rate_hz;
      const double grade = interpolate(spec.grade_profile_rad, s.distance_m);
      const Forces f = forces_at(spec.car, s, grade);
      if (i == 0) {
        log.samples.push_back(read_sensors(spec, s, f, t, rng));
        log.grade_rad.push_back(f.grade_rad);
      }
      const double command = driver_command_n(spec, s, t, f.grade_rad);
      s.force_n += (command - s.force_n) * dt_s / spec.car.force_lag_s;
      s.speed_mps = std::max(0.0, s.speed_mps + f.accel_mps2 * dt_s);
      s.distance_m += s.speed_mps * dt_s;
      update_gear(spec.car, dt_s, &s);
    }
  }
  return log;
}

NominalVehicle nominal_of(const DriveCar& car, double empty_mass_kg) {
  NominalVehicle v;
  v.empty_mass_kg = empty_mass_kg;
  v.wheel_radius_m = car.wheel_radius_m;
  v.brake_gain_n_per_pa = car.brake_gain_n_per_pa;
  v.rotating_mass_kg = car.rotating_mass_kg;
  v.drag_area_m2 = car.drag_area_m2;
  v.air_density_kg_per_m3 = car.air_density_kg_per_m3;
  v.rolling_resistance_coeff = car.rolling_resistance_coeff;
  v.gravity_mps2 = car.gravity_mps2;
  return v;
}

}  // namespace vmass::baselines::testing

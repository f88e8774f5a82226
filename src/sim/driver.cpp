#include "vmass/sim/driver.hpp"
#include "vmass/core/constants.hpp"

#include <algorithm>
#include <cmath>

namespace vmass::sim {

namespace {
constexpr double kHoldSpeedMps = 0.5;
}  // namespace

std::string DriverProfile::validate() const {
  if (auto m = speed_mps.validate("driver.speed_mps"); !m.empty()) return m;
  for (const auto& p : speed_mps.points()) {
    if (p.y < 0.0 || p.y > 60.0) return "driver.speed_mps: speeds must be in [0, 60] m/s";
  }
  if (auto m = steering_wheel_angle_rad.validate("driver.steering_wheel_angle_rad"); !m.empty()) {
    return m;
  }
  for (const SteeringSine& s : steering_sines) {
    if (!(s.end_s > s.start_s) || !(s.frequency_hz > 0.0) || !std::isfinite(s.amplitude_rad)) {
      return "driver.steering_sines: each needs end_s > start_s, frequency_hz > 0";
    }
  }
  if (circle && !(circle->radius_m > 5.0)) return "driver.circle.radius_m must be > 5";
  if (hold_reached_speed_from_s && !(*hold_reached_speed_from_s >= 0.0)) {
    return "driver.hold_reached_speed_from_s must be >= 0";
  }
  return "";
}

std::string DriverParams::validate() const {
  if (!(nominal_mass_kg > 0.0)) return "driver.nominal_mass_kg must be > 0";
  if (!(speed_gain_per_s > 0.0)) return "driver.speed_gain_per_s must be > 0";
  if (!(speed_integral_gain_per_s2 >= 0.0)) return "driver.speed_integral_gain_per_s2 must be >= 0";
  if (!(coast_band_n >= 0.0)) return "driver.coast_band_n must be >= 0";
  if (!(hold_pressure_pa > 0.0)) return "driver.hold_pressure_pa must be > 0";
  if (!(max_brake_pressure_pa >= hold_pressure_pa)) {
    return "driver.max_brake_pressure_pa must be >= hold_pressure_pa";
  }
  if (!(brake_time_constant_s > 0.0)) return "driver.brake_time_constant_s must be > 0";
  if (!(lookahead_min_m > 0.0 && lookahead_time_s >= 0.0)) return "driver.lookahead must be > 0";
  if (!(steering_time_constant_s > 0.0)) return "driver.steering_time_constant_s must be > 0";
  if (!(regen_max_force_n >= 0.0 && regen_min_speed_mps > 0.0)) {
    return "driver.regen_max_force_n must be >= 0 and regen_min_speed_mps > 0";
  }
  return "";
}

Driver::Driver(const DriverParams& params, const DriverProfile& profile, const TrueVehicle& vehicle)
    : p_(params), profile_(profile), vehicle_(vehicle) {}

void Driver::reset(double t_s, const VehicleState& s) {
  speed_integral_ = 0.0;
  radial_integral_ = 0.0;
  held_speed_mps_.reset();
  const bool hold = profile_.speed_mps(t_s) <= 0.0 && s.vx_mps < kHoldSpeedMps;
  brake_pressure_pa_ = hold ? p_.hold_pressure_pa : 0.0;
  steering_rad_ = profile_.circle ? 0.0 : open_loop_steering(t_s);
}

double Driver::open_loop_steering(double t_s) const {
  double a = profile_.steering_wheel_angle_rad(t_s);
  for (const SteeringSine& s : profile_.steering_sines) {
    if (t_s <= s.start_s || t_s >= s.end_s) continue;
    const double fade = 0.25 / s.frequency_hz;
    const double w = std::clamp(std::min(t_s - s.start_s, s.end_s - t_s) / fade, 0.0, 1.0);
    a += s.amplitude_rad * w * std::sin(2.0 * kPi * s.frequency_hz * (t_s - s.start_s));
  }
  return a;
}

double Driver::circle_steering(double dt_s, const VehicleState& s) {
  const CircleCourse& c = *profile_.circle;
  const double sgn = c.left ? 1.0 : -1.0;
  const double cx = 0.0;
  const double cy = sgn * c.radius_m;
  const double rx = s.x_m - cx;
  const double ry = s.y_m - cy;
  const double dist = std::hypot(rx, ry);
  const double ang = std::atan2(ry, rx);
  const double v = std::max(0.0, s.vx_mps);
  const double look = std::max(p_.lookahead_min_m, p_.lookahead_time_s * v);
  const double ang_t = ang + sgn * look / c.radius_m;
  const double dx = cx + c.radius_m * std::cos(ang_t) - s.x_m;
  const double dy = cy + c.radius_m * std::sin(ang_t) - s.y_m;
  const double cpsi = std::cos(s.yaw_rad);
  const double spsi = std::sin(s.yaw_rad);
  const double bx = dx * cpsi + dy * spsi;
  const double by = -dx * spsi + dy * cpsi;
  const double eta = std::atan2(by, bx);
  const double ld = std::max(1e-3, std::hypot(dx, dy));
  const double delta_pp = std::atan(2.0 * vehicle_.wheelbase_m * std::sin(eta) / ld);
  if (v > 1.0) radial_integral_ += (dist - c.radius_m) * dt_s;
  const double delta = delta_pp + sgn * p_.radial_integral_gain_rad_per_m_s * radial_integral_;
  const double cmd = std::clamp(delta, -0.6, 0.6) * vehicle_.steering_ratio;
  steering_rad_ += (cmd - steering_rad_) * (1.0 - std::exp(-dt_s / p_.steering_time_constant_s));
  return steering_rad_;
}

DriverCommand Driver::update(double t_s, double dt_s, const VehicleState& s) {
  DriverCommand cmd;
  const double v = s.vx_mps;
  if (profile_.hold_reached_speed_from_s && !held_speed_mps_ &&
      t_s >= *profile_.hold_reached_speed_from_s) {
    held_speed_mps_ = v;
    speed_integral_ = 0.0;
  }
  const double v_ref = held_speed_mps_ ? *held_speed_mps_ : profile_.speed_mps(t_s);
  const double a_ref = held_speed_mps_ ? 0.0 : profile_.speed_mps.slope(t_s);
  double pressure_cmd = 0.0;
  if (v_ref <= 0.0 && v < kHoldSpeedMps) {
    pressure_cmd = p_.hold_pressure_pa;
    speed_integral_ = 0.0;
  } else {
    const double m = p_.nominal_mass_kg;
    const double err = v_ref - v;
    const double resist =
        v > 0.1 ? 0.5 * vehicle_.air_density_kg_per_m3 * vehicle_.drag_area_m2 * v * v +
                      vehicle_.rolling_resistance_coeff * m * vehicle_.gravity_mps2
                : 0.0;
    speed_integral_ += err * dt_s;
    const double i_limit = 3000.0 / (p_.speed_integral_gain_per_s2 * m + 1e-9);
    speed_integral_ = std::clamp(speed_integral_, -i_limit, i_limit);
    const double force = m * (a_ref + p_.speed_gain_per_s * err) +
                         p_.speed_integral_gain_per_s2 * m * speed_integral_ + resist;
    double remaining = force;
    if (force < 0.0 && p_.regen_max_force_n > 0.0 && v > p_.regen_min_speed_mps) {
      const double regen = std::max(force, -p_.regen_max_force_n);
      cmd.wheel_torque_demand_nm = regen * vehicle_.wheel_radius_m;
      remaining = force - regen;
    }
    if (remaining > 0.0) {
      cmd.wheel_torque_demand_nm = remaining * vehicle_.wheel_radius_m;
    } else if (remaining < -p_.coast_band_n) {
      pressure_cmd = std::min(p_.max_brake_pressure_pa,
                              (-remaining - p_.coast_band_n) / vehicle_.brake_gain_n_per_pa);
    }
  }
  brake_pressure_pa_ +=
      (pressure_cmd - brake_pressure_pa_) * (1.0 - std::exp(-dt_s / p_.brake_time_constant_s));
  cmd.brake_pressure_pa = brake_pressure_pa_;
  cmd.steering_wheel_angle_rad =
      profile_.circle ? circle_steering(dt_s, s) : open_loop_steering(t_s);
  return cmd;
}

}  // namespace vmass::sim

#include "vmass/sim/sensor_model.hpp"

#include <algorithm>
#include <cmath>

namespace vmass::sim {

namespace {

constexpr double kTwoPi = 6.28318530717958647692;

std::uint64_t splitmix64(std::uint64_t x) {
  x += 0x9E3779B97F4A7C15ULL;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ULL;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBULL;
  return x ^ (x >> 31);
}

std::string check_channel(const char* name, const ChannelSpec& c) {
  if (!(c.noise_std >= 0.0) || !std::isfinite(c.noise_std)) {
    return std::string("sensors.") + name + ".noise_std must be >= 0";
  }
  if (!std::isfinite(c.bias)) return std::string("sensors.") + name + ".bias must be finite";
  if (!(c.resolution >= 0.0) || !std::isfinite(c.resolution)) {
    return std::string("sensors.") + name + ".resolution must be >= 0";
  }
  return "";
}

}  // namespace

std::string_view noise_set_name(NoiseSet n) {
  switch (n) {
    case NoiseSet::kNone:
      return "none";
    case NoiseSet::kEps1:
      return "eps1";
    case NoiseSet::kEps2:
      return "eps2";
    case NoiseSet::kEps3:
      return "eps3";
  }
  return "none";
}

std::optional<NoiseSet> parse_noise_set(std::string_view name) {
  for (NoiseSet n : {NoiseSet::kNone, NoiseSet::kEps1, NoiseSet::kEps2, NoiseSet::kEps3}) {
    if (noise_set_name(n) == name) return n;
  }
  return std::nullopt;
}

SensorSpec SensorSpec::ideal() {
  SensorSpec s;
  s.wheel_torque_resolution_nm = 0.0;
  s.brake_pressure_pa = {};
  s.accel_x_mps2 = {};
  s.accel_y_mps2 = {};
  s.yaw_rate_radps = {};
  s.speed_mps = {};
  s.speed_scale_error = 0.0;
  s.speed_min_mps = 0.0;
  s.steering_wheel_angle_rad = {};
  s.rear_right_deflection_m = {};
  return s;
}

std::string SensorSpec::validate() const {
  if (!(wheel_torque_resolution_nm >= 0.0))
    return "sensors.wheel_torque_resolution_nm must be >= 0";
  for (auto [name, c] :
       {std::pair{"brake_pressure_pa", &brake_pressure_pa},
        std::pair{"accel_x_mps2", &accel_x_mps2}, std::pair{"accel_y_mps2", &accel_y_mps2},
        std::pair{"yaw_rate_radps", &yaw_rate_radps}, std::pair{"speed_mps", &speed_mps},
        std::pair{"steering_wheel_angle_rad", &steering_wheel_angle_rad},
        std::pair{"rear_right_deflection_m", &rear_right_deflection_m}}) {
    if (auto m = check_channel(name, *c); !m.empty()) return m;
  }
  if (!(std::abs(speed_scale_error) < 0.1))
    return "sensors.speed_scale_error must be in (-0.1, 0.1)";
  if (!(speed_min_mps >= 0.0)) return "sensors.speed_min_mps must be >= 0";
  return "";
}

double quantise(double value, double resolution) {
  if (!(resolution > 0.0)) return value;
  return std::round(value / resolution) * resolution;
}

SensorModel::SensorModel(const SensorSpec& spec, NoiseSet noise, std::uint64_t seed,
                         double wheel_radius_m)
    : spec_(spec), noise_(noise), wheel_radius_m_(wheel_radius_m) {
  for (std::size_t i = 0; i < kStreamCount; ++i) {
    streams_[i].seed(splitmix64(seed ^ splitmix64(0xA5A5A5A5ULL + i)));
  }
}

double SensorModel::uniform(Stream s) {
  // 53 random bits -> [0, 1), independent of the standard library's distributions.
  return static_cast<double>(streams_[s]() >> 11) * 0x1.0p-53;
}

double SensorModel::normal(Stream s) {
  const double u1 = 1.0 - uniform(s);  // (0, 1]
  const double u2 = uniform(s);
  return std::sqrt(-2.0 * std::log(u1)) * std::cos(kTwoPi * u2);
}

double SensorModel::channel(Stream s, const ChannelSpec& c, double value) {
  const double n = c.noise_std > 0.0 ? c.noise_std * normal(s) : 0.0;
  return quantise(value + c.bias + n, c.resolution);
}

Sample SensorModel::measure(TimeUs t_us, const TrueSignals& truth) {
  Sample out;
  out.time_us = t_us;

  double eps = 0.0;
  switch (noise_) {
    case NoiseSet::kNone:
      break;
    case NoiseSet::kEps1:
      eps = 60.0 * normal(kTorque);
      break;
    case NoiseSet::kEps2:
      eps = 300.0 + 60.0 * normal(kTorque);
      break;
    case NoiseSet::kEps3:
      eps = 600.0 * uniform(kTorque);
      break;
  }
  last_eps_n_ = eps;
  out.set(Input::kWheelTorque, quantise(truth.wheel_torque_nm + eps * wheel_radius_m_,
                                        spec_.wheel_torque_resolution_nm));

  out.set(Input::kBrakePressure,
          std::max(0.0, channel(kBrake, spec_.brake_pressure_pa, truth.brake_pressure_pa)));
  out.set(Input::kAccelX, channel(kAx, spec_.accel_x_mps2, truth.accel_x_mps2));
  out.set(Input::kAccelY, channel(kAy, spec_.accel_y_mps2, truth.accel_y_mps2));
  out.set(Input::kYawRate, channel(kYaw, spec_.yaw_rate_radps, truth.yaw_rate_radps));

  // Draw the speed noise every tick so the stream does not depend on the speed history.
  const double speed =
      channel(kSpeed, spec_.speed_mps, truth.speed_mps * (1.0 + spec_.speed_scale_error));
  out.set(Input::kSpeed, truth.speed_mps < spec_.speed_min_mps || truth.speed_mps <= 0.0
                             ? 0.0
                             : std::max(0.0, speed));
  out.set(Input::kSteeringWheelAngle,
          channel(kSteer, spec_.steering_wheel_angle_rad, truth.steering_wheel_angle_rad));
  out.set(Input::kRearRightDeflection,
          channel(kDeflection, spec_.rear_right_deflection_m, truth.rear_right_deflection_m));
  out.set(Input::kGear, static_cast<double>(truth.gear));
  return out;
}

}  // namespace vmass::sim

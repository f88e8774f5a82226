// Sample: the estimator's inputs at one tick, in SI units and the ISO 8855 frame.
//
// Frame and signs (ISO 8855): x forward, y left, z up; yaw rate positive turning left;
// steering-wheel angle positive turning left; accelerations are what a body-fixed accelerometer
// measures (specific force, so a road grade shows up in accel_x). The rear-right suspension
// deflection is positive in compression (more load, larger value), as the sensor reads it.
//
// Each input has a validity bit: an input that is stale, out of range or was never received is
// invalid, and its value must not be used. Sample is a plain value type; thread-safe to copy.
#pragma once

#include <cstdint>
#include <string_view>

#include "vmass/core/time.hpp"

namespace vmass {

/// The estimator inputs, in the order of Sample's fields.
enum class Input : std::uint8_t {
  kWheelTorque = 0,      ///< total driving torque at the wheels, N*m (sum over driven axles)
  kBrakePressure,        ///< master-cylinder brake pressure, Pa
  kAccelX,               ///< longitudinal acceleration (specific force), m/s^2
  kAccelY,               ///< lateral acceleration (specific force), m/s^2
  kYawRate,              ///< yaw rate, rad/s
  kSpeed,                ///< longitudinal vehicle speed, m/s
  kSteeringWheelAngle,   ///< steering-wheel angle, rad
  kRearRightDeflection,  ///< rear-right suspension deflection, m (compression positive)
  kGear,                 ///< engaged gear (1..N, 0 neutral, -1 reverse); optional input
  kBrakeSwitch,          ///< brake-light switch (1 pressed), where no pressure is on the bus
  kEngineTorque,         ///< engine (or motor) torque, N*m, where no wheel torque is on the bus
  kEngineSpeed,          ///< engine (or motor) speed, rad/s (converter slip)
  kCount
};

constexpr int kInputCount = static_cast<int>(Input::kCount);

/// Bit set of inputs, bit i for Input(i).
using InputMask = std::uint32_t;

constexpr InputMask input_bit(Input in) { return InputMask{1} << static_cast<unsigned>(in); }
constexpr InputMask kAllInputs = (InputMask{1} << kInputCount) - 1;

/// Stable snake_case name of an input, as used in config keys and CSV headers.
std::string_view input_name(Input in);

struct Sample {
  TimeUs time_us = 0;
  double wheel_torque_nm = 0.0;
  double brake_pressure_pa = 0.0;
  double accel_x_mps2 = 0.0;
  double accel_y_mps2 = 0.0;
  double yaw_rate_radps = 0.0;
  double speed_mps = 0.0;
  double steering_wheel_angle_rad = 0.0;
  double rear_right_deflection_m = 0.0;
  int gear = 0;
  bool brake_switch = false;
  double engine_torque_nm = 0.0;
  double engine_speed_radps = 0.0;
  InputMask valid = 0;

  bool has(Input in) const { return (valid & input_bit(in)) != 0; }
  bool has_all(InputMask mask) const { return (valid & mask) == mask; }
  /// Value of a numeric input (gear as a double).
  double value(Input in) const;
  void set(Input in, double v);
};

}  // namespace vmass

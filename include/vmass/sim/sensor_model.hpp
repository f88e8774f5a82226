// SensorModel: turns the simulated car's true signals into the estimator's inputs (a Sample) the
// way the car's ECUs would put them on CAN at 100 Hz: noise, a small bias, quantisation.
//
// ALL NOISE LEVELS ARE HERE (SensorSpec defaults), per 100 Hz sample, white, Gaussian unless said:
//
//   signal                  noise std          bias / offset              resolution
//   wheel_torque_nm         eps * r_w (NoiseSet, below)                   0.5 N*m
//   brake_pressure_pa       3 kPa (0.03 bar)   +5 kPa (clipped at 0)      5 kPa (0.05 bar)
//   accel_x_mps2            0.02 m/s^2         +0.03 m/s^2                0.01 m/s^2
//   accel_y_mps2            0.02 m/s^2         -0.02 m/s^2                0.01 m/s^2
//   yaw_rate_radps          0.0015 rad/s       +0.0015 rad/s (0.086 deg/s) 0.01 deg/s
//   speed_mps (wheel speed) 0.02 m/s           scale +0.2 %; 0 below 0.1 m/s   0.01 km/h
//   steering_wheel_angle    0.1 deg            +0.5 deg                   0.1 deg
//   rear_right_deflection_m 0.15 mm            +0.2 mm zero offset        0.01 mm
//   gear                    exact (0 while the clutch is open during a shift)
//
// Wheel-force noise sets of the paper (eps is a force, N; the torque signal gets eps * r_w):
//   none: eps = 0;  eps1 ~ N(0, 60^2);  eps2 ~ N(300, 60^2);  eps3 ~ U(0, 600)
//
// Randomness: each signal has its own std::mt19937_64 stream seeded from (seed, signal) with
// splitmix64, and normals come from Box-Muller on 53-bit uniforms, so the same seed gives the
// same numbers on every platform with the same libm and changing the noise set of one signal
// does not move the noise of the others.
//
// Not thread-safe (random streams); one instance per simulation.
#pragma once

#include <cstdint>
#include <optional>
#include <random>
#include <string>
#include <string_view>

#include "vmass/core/sample.hpp"

namespace vmass::sim {

enum class NoiseSet : std::uint8_t { kNone, kEps1, kEps2, kEps3 };

std::string_view noise_set_name(NoiseSet n);
std::optional<NoiseSet> parse_noise_set(std::string_view name);

/// Noise, bias and CAN resolution of one signal (resolution 0: not quantised).
struct ChannelSpec {
  double noise_std = 0.0;
  double bias = 0.0;
  double resolution = 0.0;
};

struct SensorSpec {
  double wheel_torque_resolution_nm = 0.5;
  ChannelSpec brake_pressure_pa{3000.0, 5000.0, 5000.0};
  ChannelSpec accel_x_mps2{0.02, 0.03, 0.01};
  ChannelSpec accel_y_mps2{0.02, -0.02, 0.01};
  ChannelSpec yaw_rate_radps{0.0015, 0.0015, 0.01 * 3.14159265358979323846 / 180.0};
  ChannelSpec speed_mps{0.02, 0.0, 0.01 / 3.6};
  double speed_scale_error = 0.002;  ///< wheel speed reads v (1 + this)
  double speed_min_mps = 0.1;        ///< wheel-speed sensors read 0 below this
  ChannelSpec steering_wheel_angle_rad{0.1 * 3.14159265358979323846 / 180.0,
                                       0.5 * 3.14159265358979323846 / 180.0,
                                       0.1 * 3.14159265358979323846 / 180.0};
  ChannelSpec rear_right_deflection_m{0.00015, 0.0002, 0.00001};

  /// No noise, no bias, no quantisation, no speed threshold (for tests with known answers).
  static SensorSpec ideal();
  std::string validate() const;
};

/// The true values the sensors look at, in the Sample's units and frame.
struct TrueSignals {
  double wheel_torque_nm = 0.0;
  double brake_pressure_pa = 0.0;
  double accel_x_mps2 = 0.0;  ///< specific force
  double accel_y_mps2 = 0.0;
  double yaw_rate_radps = 0.0;
  double speed_mps = 0.0;  ///< v_x
  double steering_wheel_angle_rad = 0.0;
  double rear_right_deflection_m = 0.0;  ///< z - z_ref (no offset, no noise)
  int gear = 0;
};

/// What the sensor model measures: the paper's car has wheel torque and brake pressure on its
/// bus, so no brake switch, engine torque or engine speed (population vehicles get those from
/// their VehicleBus).
inline constexpr InputMask kSensorModelInputs = (input_bit(Input::kGear) << 1) - 1;

class SensorModel {
 public:
  SensorModel(const SensorSpec& spec, NoiseSet noise, std::uint64_t seed, double wheel_radius_m);

  /// The measured Sample at time t_us (all inputs valid).
  Sample measure(TimeUs t_us, const TrueSignals& truth);

  /// eps, N, drawn for the last measured wheel-torque value.
  double last_wheel_force_noise_n() const { return last_eps_n_; }

 private:
  enum Stream : std::size_t {
    kTorque = 0,
    kBrake,
    kAx,
    kAy,
    kYaw,
    kSpeed,
    kSteer,
    kDeflection,
    kStreamCount
  };
  double normal(Stream s);
  double uniform(Stream s);
  double channel(Stream s, const ChannelSpec& c, double value);

  SensorSpec spec_;
  NoiseSet noise_;
  double wheel_radius_m_;
  std::mt19937_64 streams_[kStreamCount];
  double last_eps_n_ = 0.0;
};

/// Round value to a multiple of resolution (unchanged when resolution <= 0).
double quantise(double value, double resolution);

}  // namespace vmass::sim

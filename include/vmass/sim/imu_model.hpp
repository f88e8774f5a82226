// ImuModel: the body-fixed accelerometer and yaw-rate gyro of the ESC unit, stepped at the
// simulator's integration rate (1 kHz) so that vibration, its filtering and the aliasing of the
// 100 Hz sampling downstream are real. Its outputs are the signals as the ESC ECU reads them; the
// white noise and quantisation of each transmitted sample are added where the ECU samples them
// (EcuSampler).
//
// From the true specific force f at the centre of gravity (what the estimator's model calls
// a_x, a_y; includes g sin(grade)), yaw rate r and yaw acceleration r':
//   lever arm (imu_mounting), sensor at (x_s, y_s) from the CG, x forward:
//     f_x += -r' y_s - r^2 x_s,        f_y += r' x_s - r^2 y_s
//   body pitch and roll (body_pitch_roll), driven by the body's lagged accelerations:
//     theta = k_pitch a_x,lag (nose up under acceleration, down under braking)
//     phi   = k_roll  a_y,lag (body rolls out of the turn)
//     f_x' = f_x cos(theta) + g sin(theta),   f_y' = f_y cos(phi) + g sin(phi)
//     so a pitch gradient of 1 deg/g over-reads changes of a_x by 1.7 %.
//   misalignment (imu_mounting): a yaw angle mixes x and y; a pitch/roll angle adds g sin().
//   vibration (imu_vibration): band-pass noise around f_vib (8-25 Hz) with RMS
//     A_ref (v / 30 m/s) (1 + roughness), plus the engine's firing order (cylinders / 2 per
//     revolution) with amplitude A_engine.
//   bias and drift (imu_bias_drift): constant bias plus a random walk.
//   filter (imu_filter): the sensor's own second-order Butterworth low-pass at filter_cutoff_hz.
// The gyro reads r plus its bias (imu_bias_drift).
//
// Not thread-safe; no allocation after construction.
#pragma once

#include <cstdint>
#include <string>

#include "vmass/core/low_pass_filter.hpp"
#include "vmass/sim/random_stream.hpp"
#include "vmass/sim/realism.hpp"

namespace vmass::sim {

struct ImuParams {
  double filter_cutoff_hz = 30.0;
  double bias_x_mps2 = 0.03;
  double bias_y_mps2 = -0.02;
  double drift_mps2_per_sqrt_s = 0.0005;  ///< random-walk density of each accelerometer bias
  double noise_std_mps2 = 0.02;           ///< white, per transmitted sample (EcuSampler)
  double gyro_bias_radps = 0.0015;
  double gyro_noise_std_radps = 0.0015;
  double vibration_rms_mps2 = 0.04;  ///< A_ref: at 30 m/s on a smooth road
  double vibration_frequency_hz = 12.0;
  double vibration_q = 2.0;             ///< band-pass quality factor
  double engine_vibration_mps2 = 0.03;  ///< firing-order amplitude
  int engine_cylinders = 4;             ///< 0: no engine (electric)
  double lever_forward_m = 0.2;         ///< sensor position relative to the empty car's CG
  double lever_left_m = 0.0;
  double misalignment_yaw_rad = 0.0;
  double misalignment_pitch_rad = 0.0;
  double misalignment_roll_rad = 0.0;
  double pitch_per_accel_rad_per_mps2 = 0.00178;  ///< 1 deg/g
  double roll_per_accel_rad_per_mps2 = 0.0071;    ///< 4 deg/g

  std::string validate(const std::string& prefix) const;
};

/// What the IMU looks at during one integration step.
struct ImuInput {
  double specific_force_x_mps2 = 0.0;  ///< at the CG
  double specific_force_y_mps2 = 0.0;
  double yaw_rate_radps = 0.0;
  double yaw_accel_radps2 = 0.0;
  double body_accel_x_mps2 = 0.0;  ///< lagged accelerations that tilt the body
  double body_accel_y_mps2 = 0.0;
  double speed_mps = 0.0;
  double roughness = 0.0;  ///< road roughness scale (0 smooth, ~1 rough, ~3 very rough)
  double engine_speed_radps = 0.0;
  double cg_shift_forward_m = 0.0;  ///< loaded CG ahead of the empty CG (moves the lever arm)
  double cg_shift_left_m = 0.0;
};

struct ImuOutput {
  double accel_x_mps2 = 0.0;
  double accel_y_mps2 = 0.0;
  double yaw_rate_radps = 0.0;
};

class ImuModel {
 public:
  ImuModel(const ImuParams& params, double rate_hz, double gravity_mps2, std::uint64_t seed,
           Realism effects);

  ImuOutput step(const ImuInput& in);

 private:
  struct BandPass {  // RBJ band-pass biquad (constant 0 dB peak gain)
    double b0 = 0, b2 = 0, a1 = 0, a2 = 0;
    double x1 = 0, x2 = 0, y1 = 0, y2 = 0;
    double step(double x);
  };
  double vibration(const ImuInput& in, BandPass& band, RandomStream& rng, double phase_offset);

  ImuParams p_;
  double dt_s_;
  double g_;
  Realism effects_;
  vmass::LowPassFilter filter_x_, filter_y_;
  BandPass band_x_, band_y_;
  RandomStream vib_x_rng_, vib_y_rng_, drift_rng_;
  double drive_gain_ = 0.0;  ///< white-noise std that gives unit RMS out of the band-pass
  double drift_x_ = 0.0, drift_y_ = 0.0;
  double engine_phase_ = 0.0;
};

}  // namespace vmass::sim

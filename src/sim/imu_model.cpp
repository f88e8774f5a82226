#include "vmass/sim/imu_model.hpp"

#include <cmath>

namespace vmass::sim {

namespace {
constexpr double kTwoPi = 6.28318530717958647692;
constexpr double kVibrationReferenceSpeedMps = 30.0;
}  // namespace

std::string ImuParams::validate(const std::string& prefix) const {
  if (!(filter_cutoff_hz > 0.0)) return prefix + "filter_cutoff_hz must be > 0";
  if (!(noise_std_mps2 >= 0.0 && gyro_noise_std_radps >= 0.0 && drift_mps2_per_sqrt_s >= 0.0)) {
    return prefix + "noise and drift must be >= 0";
  }
  if (!(vibration_rms_mps2 >= 0.0 && engine_vibration_mps2 >= 0.0)) {
    return prefix + "vibration amplitudes must be >= 0";
  }
  if (!(vibration_frequency_hz > 0.0 && vibration_q > 0.1)) {
    return prefix + "vibration_frequency_hz must be > 0 and vibration_q > 0.1";
  }
  if (engine_cylinders < 0 || engine_cylinders > 16) return prefix + "engine_cylinders in 0..16";
  return "";
}

double ImuModel::BandPass::step(double x) {
  const double y = b0 * x + b2 * x2 - a1 * y1 - a2 * y2;
  x2 = x1;
  x1 = x;
  y2 = y1;
  y1 = y;
  return y;
}

ImuModel::ImuModel(const ImuParams& params, double rate_hz, double gravity_mps2, std::uint64_t seed,
                   Realism effects)
    : p_(params),
      dt_s_(1.0 / rate_hz),
      g_(gravity_mps2),
      effects_(effects),
      vib_x_rng_(seed, hash_name("imu.vibration.x")),
      vib_y_rng_(seed, hash_name("imu.vibration.y")),
      drift_rng_(seed, hash_name("imu.drift")) {
  if (effects.has(Effect::kImuFilter) && params.filter_cutoff_hz < 0.5 * rate_hz) {
    filter_x_ = vmass::LowPassFilter(params.filter_cutoff_hz, rate_hz);
    filter_y_ = vmass::LowPassFilter(params.filter_cutoff_hz, rate_hz);
  }
  const double w0 = kTwoPi * params.vibration_frequency_hz / rate_hz;
  const double alpha = std::sin(w0) / (2.0 * params.vibration_q);
  const double a0 = 1.0 + alpha;
  BandPass b;
  b.b0 = alpha / a0;
  b.b2 = -alpha / a0;
  b.a1 = -2.0 * std::cos(w0) / a0;
  b.a2 = (1.0 - alpha) / a0;
  // White noise of std s gives an output variance s^2 sum(h^2): scale for unit RMS.
  BandPass probe = b;
  double energy = 0.0;
  for (int k = 0; k < 50000; ++k) {
    const double h = probe.step(k == 0 ? 1.0 : 0.0);
    energy += h * h;
  }
  drive_gain_ = energy > 0.0 ? 1.0 / std::sqrt(energy) : 0.0;
  band_x_ = b;
  band_y_ = b;
}

double ImuModel::vibration(const ImuInput& in, BandPass& band, RandomStream& rng,
                           double phase_offset) {
  // Draw every step, so the stream does not depend on the speed history.
  const double road = band.step(drive_gain_ * rng.normal());
  const double speed_scale = std::abs(in.speed_mps) / kVibrationReferenceSpeedMps;
  double v = p_.vibration_rms_mps2 * speed_scale * (1.0 + in.roughness) * road;
  if (p_.engine_cylinders > 0 && in.engine_speed_radps > 0.0) {
    v += p_.engine_vibration_mps2 * std::sin(engine_phase_ + phase_offset);
  }
  return v;
}

ImuOutput ImuModel::step(const ImuInput& in) {
  double fx = in.specific_force_x_mps2;
  double fy = in.specific_force_y_mps2;
  if (effects_.has(Effect::kImuMounting)) {
    const double xs = p_.lever_forward_m - in.cg_shift_forward_m;
    const double ys = p_.lever_left_m - in.cg_shift_left_m;
    const double r = in.yaw_rate_radps;
    const double rd = in.yaw_accel_radps2;
    fx += -rd * ys - r * r * xs;
    fy += rd * xs - r * r * ys;
  }
  if (effects_.has(Effect::kBodyPitchRoll)) {
    const double pitch = p_.pitch_per_accel_rad_per_mps2 * in.body_accel_x_mps2;
    const double roll = p_.roll_per_accel_rad_per_mps2 * in.body_accel_y_mps2;
    fx = fx * std::cos(pitch) + g_ * std::sin(pitch);
    fy = fy * std::cos(roll) + g_ * std::sin(roll);
  }
  if (effects_.has(Effect::kImuMounting)) {
    const double c = std::cos(p_.misalignment_yaw_rad);
    const double s = std::sin(p_.misalignment_yaw_rad);
    const double x = c * fx + s * fy + g_ * std::sin(p_.misalignment_pitch_rad);
    const double y = -s * fx + c * fy + g_ * std::sin(p_.misalignment_roll_rad);
    fx = x;
    fy = y;
  }
  if (effects_.has(Effect::kImuVibration)) {
    const double firing_hz =
        in.engine_speed_radps / kTwoPi * 0.5 * static_cast<double>(p_.engine_cylinders);
    engine_phase_ = std::fmod(engine_phase_ + kTwoPi * firing_hz * dt_s_, kTwoPi);
    fx += vibration(in, band_x_, vib_x_rng_, 0.0);
    fy += 0.6 * vibration(in, band_y_, vib_y_rng_, 1.3);
  }
  if (effects_.has(Effect::kImuBiasDrift)) {
    const double step = p_.drift_mps2_per_sqrt_s * std::sqrt(dt_s_);
    drift_x_ += step * drift_rng_.normal();
    drift_y_ += step * drift_rng_.normal();
    fx += p_.bias_x_mps2 + drift_x_;
    fy += p_.bias_y_mps2 + drift_y_;
  }
  ImuOutput out;
  out.accel_x_mps2 = filter_x_.step(fx);
  out.accel_y_mps2 = filter_y_.step(fy);
  out.yaw_rate_radps =
      in.yaw_rate_radps + (effects_.has(Effect::kImuBiasDrift) ? p_.gyro_bias_radps : 0.0);
  return out;
}

}  // namespace vmass::sim

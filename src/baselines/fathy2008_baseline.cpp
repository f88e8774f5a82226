#include "vmass/baselines/fathy2008_baseline.hpp"

#include <algorithm>
#include <cmath>

namespace vmass::baselines {
namespace {

double prior_mass_std(const Fathy2008Params& params, const NominalVehicle& vehicle) {
  return params.prior_mass_std_kg > 0.0 ? params.prior_mass_std_kg : vehicle.empty_mass_kg;
}

}  // namespace

std::string Fathy2008Params::validate() const {
  if (!(high_pass_hz > 0.0)) return "high_pass_hz must be > 0";
  if (!(low_pass_hz > high_pass_hz)) return "low_pass_hz must be > high_pass_hz";
  if (!(min_abs_filtered_accel_mps2 > 0.0)) return "min_abs_filtered_accel_mps2 must be > 0";
  if (!(max_abs_accel_y_mps2 > 0.0)) return "max_abs_accel_y_mps2 must be > 0";
  if (!(min_speed_mps >= 0.0)) return "min_speed_mps must be >= 0";
  if (!(noise_std_n > 0.0)) return "noise_std_n must be > 0";
  if (!(prior_mass_std_kg >= 0.0)) return "prior_mass_std_kg must be >= 0";
  if (!(interval_sigmas > 0.0)) return "interval_sigmas must be > 0";
  return "";
}

Fathy2008Baseline::Fathy2008Baseline(const NominalVehicle& vehicle, double tick_rate_hz,
                                     const Fathy2008Params& params)
    : vehicle_(vehicle),
      params_(params),
      usable_(vehicle.validate().empty() && params.validate().empty() && tick_rate_hz > 0.0 &&
              params.low_pass_hz < 0.5 * tick_rate_hz),
      brake_rule_(brake_rule_for(vehicle, params.min_speed_mps)),
      continuity_(usable_ ? tick_rate_hz : 1.0),
      force_high_(params.high_pass_hz, tick_rate_hz),
      accel_high_(params.high_pass_hz, tick_rate_hz),
      force_low_(params.low_pass_hz, tick_rate_hz),
      accel_low_(params.low_pass_hz, tick_rate_hz),
      accel_y_low_(params.low_pass_hz, tick_rate_hz),
      mass_kg_(vehicle.empty_mass_kg),
      variance_kg2_(std::pow(prior_mass_std(params, vehicle), 2)),
      noise_var_n2_(params.noise_std_n * params.noise_std_n) {}

bool Fathy2008Baseline::read(const vmass::Sample& sample, Tick* tick) const {
  const auto torque_nm = read_input(sample, vmass::Input::kWheelTorque);
  const auto accel_x = read_input(sample, vmass::Input::kAccelX);
  const auto accel_y = read_input(sample, vmass::Input::kAccelY);
  const auto speed = read_input(sample, vmass::Input::kSpeed);
  if (!torque_nm || !accel_x || !accel_y || !speed || *speed < params_.min_speed_mps) {
    return false;
  }
  if (!brakes_off(brake_state(sample, brake_rule_))) return false;
  tick->force_n = *torque_nm / vehicle_.wheel_radius_m - vehicle_.rotating_mass_kg * *accel_x;
  tick->accel_x_mps2 = *accel_x;
  tick->accel_y_mps2 = *accel_y;
  tick->has_gear = sample.has(vmass::Input::kGear);
  tick->gear = sample.gear;
  return !tick->has_gear || tick->gear >= 1;  // neutral, clutch open or reverse: no model
}

void Fathy2008Baseline::restart() {
  force_high_.reset();
  accel_high_.reset();
  force_low_.reset();
  accel_low_.reset();
  accel_y_low_.reset();
}

void Fathy2008Baseline::step(const vmass::Sample& sample) {
  if (!usable_) return;
  const bool contiguous = continuity_.follows(sample.time_us);
  Tick now;
  const bool readable = read(sample, &now);
  const bool shifted =
      readable && has_previous_ && now.has_gear && previous_.has_gear && now.gear != previous_.gear;
  if (!contiguous || !readable || shifted) restart();  // a hole: never filter across it
  has_previous_ = readable;
  if (!readable) return;
  previous_ = now;
  const double force_f = force_low_.step(force_high_.step(now.force_n));
  const double accel_f = accel_low_.step(accel_high_.step(now.accel_x_mps2));
  const double accel_y_f = accel_y_low_.step(now.accel_y_mps2);
  const bool straight = std::abs(accel_y_f) < params_.max_abs_accel_y_mps2;
  const bool excited = std::abs(accel_f) >= params_.min_abs_filtered_accel_mps2;
  if (straight && excited) update(force_f, accel_f);
}

void Fathy2008Baseline::update(double y, double phi) {
  const double s = phi * variance_kg2_ * phi + noise_var_n2_;
  const double gain = variance_kg2_ * phi / s;
  const double mass_kg = mass_kg_ + gain * (y - phi * mass_kg_);
  const double variance_kg2 = (1.0 - gain * phi) * variance_kg2_;
  if (!std::isfinite(mass_kg) || !(variance_kg2 > 0.0)) return;
  mass_kg_ = mass_kg;
  variance_kg2_ = variance_kg2;
  sum_phi2_ += phi * phi;
  sum_phi_y_ += phi * y;
  sum_y2_ += y * y;
  ++updates_;
}

BaselineEstimate Fathy2008Baseline::estimate() const {
  BaselineEstimate e;
  e.updates = updates_;
  e.has_mass = updates_ > 0;
  if (!e.has_mass) return e;
  e.mass_kg = mass_kg_;
  if (updates_ >= 3 && sum_phi2_ > 0.0) {
    const double residual_ss =
        std::max(0.0, sum_y2_ - 2.0 * mass_kg_ * sum_phi_y_ + mass_kg_ * mass_kg_ * sum_phi2_);
    const double residual_var = residual_ss / static_cast<double>(updates_ - 1);
    const double half_width = params_.interval_sigmas * std::sqrt(residual_var / sum_phi2_);
    e.has_interval = true;
    e.ci_low_kg = mass_kg_ - half_width;
    e.ci_high_kg = mass_kg_ + half_width;
  }
  return e;
}

}  // namespace vmass::baselines

#include "vmass/baselines/paper_baseline.hpp"

#include <cmath>

#include "vmass/baselines/differencing_steps.hpp"

namespace vmass::baselines {
namespace {

double prior_mass_std(const PaperParams& params, const NominalVehicle& vehicle) {
  return params.prior_mass_std_kg > 0.0 ? params.prior_mass_std_kg : vehicle.empty_mass_kg;
}

}  // namespace

std::string PaperParams::validate() const {
  if (!(differencing_dt_s > 0.0)) return "differencing_dt_s must be > 0";
  if (!(max_abs_accel_y_mps2 > 0.0)) return "max_abs_accel_y_mps2 must be > 0";
  if (!(min_abs_delta_accel_x_mps2 >= 0.0)) return "min_abs_delta_accel_x_mps2 must be >= 0";
  if (!(min_abs_delta_force_n >= 0.0)) return "min_abs_delta_force_n must be >= 0";
  if (!(min_rolling_speed_mps >= 0.0)) return "min_rolling_speed_mps must be >= 0";
  if (!(noise_std_n > 0.0)) return "noise_std_n must be > 0";
  if (!(prior_mass_std_kg >= 0.0)) return "prior_mass_std_kg must be >= 0";
  if (!(prior_mu_std_n > 0.0)) return "prior_mu_std_n must be > 0";
  return "";
}

PaperBaseline::PaperBaseline(const NominalVehicle& vehicle, double tick_rate_hz,
                             const PaperParams& params)
    : vehicle_(vehicle),
      params_(params),
      usable_(vehicle.validate().empty() && params.validate().empty() && tick_rate_hz > 0.0),
      brake_rule_(brake_rule_for(vehicle, params.min_rolling_speed_mps)),
      continuity_(usable_ ? tick_rate_hz : 1.0),
      window_(differencing_steps(params.differencing_dt_s, tick_rate_hz)),
      rls_(params.noise_std_n, Eigen::Vector2d(vehicle.empty_mass_kg, 0.0),
           Eigen::Vector2d(prior_mass_std(params, vehicle), params.prior_mu_std_n)) {}

bool PaperBaseline::read(const vmass::Sample& sample, Record* record) const {
  const auto torque_nm = read_input(sample, vmass::Input::kWheelTorque);
  const auto accel_x = read_input(sample, vmass::Input::kAccelX);
  const auto accel_y = read_input(sample, vmass::Input::kAccelY);
  const auto speed = read_input(sample, vmass::Input::kSpeed);
  if (!torque_nm || !accel_x || !accel_y || !speed) return false;
  const BrakeState brakes = brake_state(sample, brake_rule_);
  if (brakes == BrakeState::kUnknown) return false;
  // An unknown gain (0) only works with the brakes off.
  if (brakes == BrakeState::kApplied && !(vehicle_.brake_gain_n_per_pa > 0.0)) return false;
  // Eq. (7) as published, at any measured pressure; none without a pressure signal.
  const double brake_force_n = brakes == BrakeState::kAssumedOff
                                   ? 0.0
                                   : sample.brake_pressure_pa * vehicle_.brake_gain_n_per_pa;
  *record = Record{sample.time_us, *torque_nm / vehicle_.wheel_radius_m - brake_force_n, *accel_x,
                   *accel_y, *speed};
  return true;
}

bool PaperBaseline::passes_gates(const Record& now, const Record& then) const {
  const bool straight = std::abs(now.accel_y_mps2) < params_.max_abs_accel_y_mps2 &&
                        std::abs(then.accel_y_mps2) < params_.max_abs_accel_y_mps2;
  const bool rolling = now.speed_mps >= params_.min_rolling_speed_mps &&
                       then.speed_mps >= params_.min_rolling_speed_mps;
  const bool excited =
      std::abs(now.accel_x_mps2 - then.accel_x_mps2) > params_.min_abs_delta_accel_x_mps2 &&
      std::abs(now.force_n - then.force_n) > params_.min_abs_delta_force_n;
  return straight && rolling && excited;
}

void PaperBaseline::step(const vmass::Sample& sample) {
  if (!usable_) return;
  const bool contiguous = continuity_.follows(sample.time_us);
  Record now;
  const bool readable = read(sample, &now);
  if (!contiguous || !readable) window_.clear();  // a hole: never difference across it
  if (!readable) return;
  const Record* then = window_.push(now);
  if (then == nullptr || !passes_gates(now, *then)) return;
  const double delta_accel = now.accel_x_mps2 - then->accel_x_mps2;
  rls_.update(now.force_n - then->force_n, Eigen::RowVector2d(delta_accel, 1.0));
}

BaselineEstimate PaperBaseline::estimate() const {
  BaselineEstimate e;
  e.updates = rls_.updates();
  e.has_mass = rls_.updates() > 0;
  if (e.has_mass) e.mass_kg = rls_.theta()[0];
  return e;
}

}  // namespace vmass::baselines

#include "vmass/baselines/paper_lp_baseline.hpp"

#include <cmath>

#include "vmass/baselines/differencing_steps.hpp"

namespace vmass::baselines {
namespace {

NigPrior make_prior(const PaperLpParams& params, const NominalVehicle& vehicle) {
  NigPrior prior;
  prior.mean = Eigen::Vector2d(vehicle.empty_mass_kg, 0.0);
  const double mass_std =
      params.prior_mass_std_kg > 0.0 ? params.prior_mass_std_kg : vehicle.empty_mass_kg;
  prior.std = Eigen::Vector2d(mass_std, params.prior_mu_std_n);
  prior.noise_std_guess = params.noise_std_guess_n;
  prior.noise_dof = params.prior_noise_dof;
  return prior;
}

}  // namespace

std::string PaperLpParams::validate() const {
  if (!(cutoff_hz > 0.0)) return "cutoff_hz must be > 0";
  if (!(differencing_dt_s > 0.0)) return "differencing_dt_s must be > 0";
  if (!(max_abs_accel_y_mps2 > 0.0)) return "max_abs_accel_y_mps2 must be > 0";
  if (!(min_abs_delta_accel_x_mps2 >= 0.0)) return "min_abs_delta_accel_x_mps2 must be >= 0";
  if (!(min_abs_delta_force_n >= 0.0)) return "min_abs_delta_force_n must be >= 0";
  if (!(min_rolling_speed_mps >= 0.0)) return "min_rolling_speed_mps must be >= 0";
  if (batch_size < 1) return "batch_size must be >= 1";
  if (!(prior_mass_std_kg >= 0.0)) return "prior_mass_std_kg must be >= 0";
  if (!(prior_mu_std_n > 0.0)) return "prior_mu_std_n must be > 0";
  if (!(noise_std_guess_n > 0.0)) return "noise_std_guess_n must be > 0";
  if (!(prior_noise_dof > 0.0)) return "prior_noise_dof must be > 0";
  if (!(credible_level > 0.0 && credible_level < 1.0)) return "credible_level must be in (0, 1)";
  return "";
}

PaperLpBaseline::PaperLpBaseline(const NominalVehicle& vehicle, double tick_rate_hz,
                                 const PaperLpParams& params)
    : vehicle_(vehicle),
      params_(params),
      usable_(vehicle.validate().empty() && params.validate().empty() && tick_rate_hz > 0.0 &&
              params.cutoff_hz < 0.5 * tick_rate_hz),
      brake_rule_(brake_rule_for(vehicle, params.min_rolling_speed_mps)),
      continuity_(usable_ ? tick_rate_hz : 1.0),
      force_filter_(params.cutoff_hz, tick_rate_hz),
      accel_x_filter_(params.cutoff_hz, tick_rate_hz),
      accel_y_filter_(params.cutoff_hz, tick_rate_hz),
      window_(differencing_steps(params.differencing_dt_s, tick_rate_hz)),
      nig_(make_prior(params, vehicle), params.batch_size) {}

bool PaperLpBaseline::read(const vmass::Sample& sample, Record* record) const {
  const auto torque_nm = read_input(sample, vmass::Input::kWheelTorque);
  const auto accel_x = read_input(sample, vmass::Input::kAccelX);
  const auto accel_y = read_input(sample, vmass::Input::kAccelY);
  const auto speed = read_input(sample, vmass::Input::kSpeed);
  if (!torque_nm || !accel_x || !accel_y || !speed) return false;
  const BrakeState brakes = brake_state(sample, brake_rule_);
  if (brakes == BrakeState::kUnknown) return false;
  if (brakes == BrakeState::kApplied && !(vehicle_.brake_gain_n_per_pa > 0.0)) return false;
  const double brake_force_n = brakes == BrakeState::kAssumedOff
                                   ? 0.0
                                   : sample.brake_pressure_pa * vehicle_.brake_gain_n_per_pa;
  *record = Record{sample.time_us, *torque_nm / vehicle_.wheel_radius_m - brake_force_n, *accel_x,
                   *accel_y, *speed};
  return true;
}

bool PaperLpBaseline::passes_gates(const Record& now, const Record& then) const {
  const bool straight = std::abs(now.accel_y_mps2) < params_.max_abs_accel_y_mps2 &&
                        std::abs(then.accel_y_mps2) < params_.max_abs_accel_y_mps2;
  const bool rolling = now.speed_mps >= params_.min_rolling_speed_mps &&
                       then.speed_mps >= params_.min_rolling_speed_mps;
  const bool excited =
      std::abs(now.accel_x_mps2 - then.accel_x_mps2) > params_.min_abs_delta_accel_x_mps2 &&
      std::abs(now.force_n - then.force_n) > params_.min_abs_delta_force_n;
  return straight && rolling && excited;
}

void PaperLpBaseline::restart() {
  force_filter_.reset();
  accel_x_filter_.reset();
  accel_y_filter_.reset();
  window_.clear();
}

void PaperLpBaseline::step(const vmass::Sample& sample) {
  if (!usable_) return;
  const bool contiguous = continuity_.follows(sample.time_us);
  Record now;
  const bool readable = read(sample, &now);
  if (!contiguous || !readable) restart();  // a hole: never filter or difference across it
  if (!readable) return;
  now.force_n = force_filter_.step(now.force_n);
  now.accel_x_mps2 = accel_x_filter_.step(now.accel_x_mps2);
  now.accel_y_mps2 = accel_y_filter_.step(now.accel_y_mps2);
  const Record* then = window_.push(now);
  if (then == nullptr || !passes_gates(now, *then)) return;
  const double delta_accel = now.accel_x_mps2 - then->accel_x_mps2;
  nig_.add(now.force_n - then->force_n, Eigen::RowVector2d(delta_accel, 1.0));
}

BaselineEstimate PaperLpBaseline::estimate() const {
  BaselineEstimate e;
  e.updates = nig_.pairs_used();
  e.has_mass = nig_.batches() > 0;
  if (!e.has_mass) return e;
  e.mass_kg = nig_.mean()[0];
  e.has_interval = true;
  nig_.mass_interval(params_.credible_level, &e.ci_low_kg, &e.ci_high_kg);
  return e;
}

}  // namespace vmass::baselines

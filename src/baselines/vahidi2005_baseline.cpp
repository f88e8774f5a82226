#include "vmass/baselines/vahidi2005_baseline.hpp"

#include <algorithm>
#include <cmath>

namespace vmass::baselines {
namespace {

double forgetting_factor(double memory_s, double tick_rate_hz) {
  return std::exp(-1.0 / (memory_s * tick_rate_hz));
}

MultipleForgettingRls make_rls(const Vahidi2005Params& params, const NominalVehicle& vehicle,
                               double tick_rate_hz) {
  const double beta_mu = std::atan(vehicle.rolling_resistance_coeff);
  const double rate = tick_rate_hz > 0.0 ? tick_rate_hz : 1.0;
  MultipleForgettingRlsParams rls;
  rls.forgetting_1 = forgetting_factor(params.mass_memory_s, rate);
  rls.forgetting_2 = forgetting_factor(params.grade_memory_s, rate);
  rls.noise_var = params.noise_std_mps2 * params.noise_std_mps2;
  rls.cross_covariance = params.cross_covariance;
  // Start: the empty mass on a level road (theta_2 = sin(beta_mu)).
  return MultipleForgettingRls(
      Eigen::Vector2d(1.0 / vehicle.empty_mass_kg, std::sin(beta_mu)),
      Eigen::Vector2d(params.prior_inverse_mass_std_fraction / vehicle.empty_mass_kg,
                      params.prior_grade_std),
      rls);
}

}  // namespace

std::string Vahidi2005Params::validate() const {
  if (!(cutoff_hz > 0.0)) return "cutoff_hz must be > 0";
  if (!(min_speed_mps >= 0.0)) return "min_speed_mps must be >= 0";
  if (!(mass_memory_s > 0.0)) return "mass_memory_s must be > 0";
  if (!(grade_memory_s > 0.0)) return "grade_memory_s must be > 0";
  if (!(noise_std_mps2 > 0.0)) return "noise_std_mps2 must be > 0";
  if (!(prior_inverse_mass_std_fraction > 0.0)) {
    return "prior_inverse_mass_std_fraction must be > 0";
  }
  if (!(prior_grade_std > 0.0)) return "prior_grade_std must be > 0";
  if (!(restart_settle_s >= 0.0)) return "restart_settle_s must be >= 0";
  if (!(shift_settle_s >= 0.0)) return "shift_settle_s must be >= 0";
  return "";
}

Vahidi2005Baseline::Vahidi2005Baseline(const NominalVehicle& vehicle, double tick_rate_hz,
                                       const Vahidi2005Params& params)
    : vehicle_(vehicle),
      params_(params),
      usable_(vehicle.validate().empty() && params.validate().empty() && tick_rate_hz > 0.0 &&
              params.cutoff_hz < 0.5 * tick_rate_hz),
      tick_rate_hz_(tick_rate_hz),
      beta_mu_rad_(std::atan(vehicle.rolling_resistance_coeff)),
      brake_rule_(brake_rule_for(vehicle, params.min_speed_mps)),
      continuity_(usable_ ? tick_rate_hz : 1.0),
      accel_filter_(params.cutoff_hz, tick_rate_hz),
      regressor_filter_(params.cutoff_hz, tick_rate_hz),
      rls_(make_rls(params, vehicle, tick_rate_hz)),
      settle_ticks_(std::lround(params.restart_settle_s * (usable_ ? tick_rate_hz : 0.0))),
      shift_settle_ticks_(std::lround(params.shift_settle_s * (usable_ ? tick_rate_hz : 0.0))) {}

bool Vahidi2005Baseline::read(const vmass::Sample& sample, Tick* tick) const {
  const auto torque_nm = read_input(sample, vmass::Input::kWheelTorque);
  const auto speed = read_input(sample, vmass::Input::kSpeed);
  if (!torque_nm || !speed) return false;
  tick->traction_force_n = *torque_nm / vehicle_.wheel_radius_m;
  tick->speed_mps = *speed;
  tick->has_gear = sample.has(vmass::Input::kGear);
  tick->gear = sample.gear;
  tick->brakes_off = brakes_off(brake_state(sample, brake_rule_));
  tick->in_gear = !tick->has_gear || tick->gear >= 1;  // not neutral, clutch open or reverse
  tick->fast_enough = *speed >= params_.min_speed_mps;
  return true;
}

void Vahidi2005Baseline::restart() {
  accel_filter_.reset();
  regressor_filter_.reset();
  has_previous_ = false;
  hold_ticks_left_ = settle_ticks_;
}

void Vahidi2005Baseline::step(const vmass::Sample& sample) {
  if (!usable_) return;
  const bool contiguous = continuity_.follows(sample.time_us);
  Tick now;
  const bool readable = read(sample, &now);
  if (!contiguous || !readable) restart();  // a hole: never filter across it
  if (!readable) return;
  const bool shifted =
      has_previous_ && now.has_gear && previous_.has_gear && now.gear != previous_.gear;
  // The estimation stops while the model does not hold and for the filters' memory after.
  if (!now.brakes_off || !now.fast_enough) {
    hold_ticks_left_ = std::max(hold_ticks_left_, settle_ticks_);
  } else if (!now.in_gear || shifted) {
    hold_ticks_left_ = std::max(hold_ticks_left_, shift_settle_ticks_);
  }
  if (has_previous_) update(now);
  previous_ = now;
  has_previous_ = true;
}

void Vahidi2005Baseline::update(const Tick& now) {
  const double accel_mps2 = (now.speed_mps - previous_.speed_mps) * tick_rate_hz_;
  const double speed_mid_mps = 0.5 * (now.speed_mps + previous_.speed_mps);
  const double traction_mid_n = 0.5 * (now.traction_force_n + previous_.traction_force_n);
  const double drag_n =
      0.5 * vehicle_.air_density_kg_per_m3 * vehicle_.drag_area_m2 * speed_mid_mps * speed_mid_mps;
  const double regressor_n = traction_mid_n - vehicle_.rotating_mass_kg * accel_mps2 - drag_n;
  const double y = accel_filter_.step(accel_mps2);
  const double phi_1 = regressor_filter_.step(regressor_n);
  if (hold_ticks_left_ > 0) {
    --hold_ticks_left_;
    return;
  }
  const double phi_2 = -vehicle_.gravity_mps2 / std::cos(beta_mu_rad_);
  rls_.update(y, phi_1, phi_2);
}

double Vahidi2005Baseline::grade_rad() const {
  return std::asin(std::clamp(rls_.theta()[1], -1.0, 1.0)) - beta_mu_rad_;
}

BaselineEstimate Vahidi2005Baseline::estimate() const {
  BaselineEstimate e;
  e.updates = rls_.updates();
  e.has_mass = rls_.updates() > 0 && rls_.theta()[0] > 0.0;
  if (e.has_mass) e.mass_kg = 1.0 / rls_.theta()[0];
  return e;
}

}  // namespace vmass::baselines

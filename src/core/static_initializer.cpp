#include "vmass/core/static_initializer.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "vmass/core/param_check.hpp"

namespace vmass {

std::string StaticInitParams::validate() const {
  ParamCheck c("estimator.static_init");
  c.non_negative("standstill_speed_mps", standstill_speed_mps);
  c.non_negative("settle_s", settle_s);
  c.positive("standstill_window_s", standstill_window_s);
  c.positive("max_deflection_std_m", max_deflection_std_m);
  c.positive("prior_std_kg", prior_std_kg);
  c.non_negative("prior_std_fraction_of_added", prior_std_fraction_of_added);
  c.positive("out_of_range_prior_std_kg", out_of_range_prior_std_kg);
  c.positive("no_static_prior_std_kg", no_static_prior_std_kg);
  c.positive("mu_prior_std_n", mu_prior_std_n);
  c.positive("load_change_sigma", load_change_sigma);
  c.non_negative("min_load_change_m", min_load_change_m);
  c.positive("max_grade_change_mps2", max_grade_change_mps2);
  return c.message();
}

StaticInitializer::StaticInitializer(const VehicleParams& vehicle,
                                     const SuspensionParams& suspension,
                                     const StaticInitParams& params)
    : vehicle_(vehicle), suspension_(suspension), params_(params) {}

double StaticInitializer::mass_from_deflection_kg(double deflection_m) const {
  const double rear_wheel_force_n = suspension_.wheel_force_n(deflection_m);
  return vehicle_.empty_mass_kg + 2.0 * vehicle_.wheelbase_m * rear_wheel_force_n /
                                      (vehicle_.cg_to_front_axle_m * vehicle_.gravity_mps2);
}

StaticMass StaticInitializer::static_mass_for(double deflection_m, double deflection_std_m) const {
  StaticMass out;
  out.deflection_m = deflection_m;
  out.deflection_std_m = deflection_std_m;
  out.prior.mass_kg = mass_from_deflection_kg(deflection_m);
  out.added_mass_kg = out.prior.mass_kg - vehicle_.empty_mass_kg;
  // The linear model is trusted up to its linear range, a calibrated progressive curve up to its
  // calibrated range; beyond, the static mass is only a rough start.
  const double trusted_kg =
      suspension_.is_progressive() ? suspension_.calibrated_range_kg : suspension_.linear_range_kg;
  out.beyond_calibrated_range = std::abs(out.added_mass_kg) > trusted_kg;
  // Eq. (3) puts the added load at the centre of gravity; a load in the boot or on the back
  // seat loads the rear more (the simulator's +250 kg in the boot reads +6.8 % too heavy), so the
  // prior widens with the added mass.
  const double in_range_std_kg =
      params_.prior_std_kg + params_.prior_std_fraction_of_added * std::abs(out.added_mass_kg);
  out.prior.mass_std_kg = out.beyond_calibrated_range
                              ? std::max(params_.out_of_range_prior_std_kg, in_range_std_kg)
                              : in_range_std_kg;
  out.prior.mu_n = 0.0;
  out.prior.mu_std_n = params_.mu_prior_std_n;
  return out;
}

MassPrior StaticInitializer::no_static_prior() const {
  MassPrior p;
  p.mass_kg = vehicle_.empty_mass_kg;
  p.mass_std_kg = params_.no_static_prior_std_kg;
  p.mu_n = 0.0;
  p.mu_std_n = params_.mu_prior_std_n;
  return p;
}

void StaticInitializer::restore_reference(double deflection_m, double deflection_std_m,
                                          double grade_accel_mps2) {
  reference_ = Reference{deflection_m, deflection_std_m, grade_accel_mps2};
}

void StaticInitializer::restart_window() {
  window_open_ = false;
  window_count_ = 0;
  window_mean_ = 0.0;
  window_m2_ = 0.0;
  grade_count_ = 0;
  grade_sum_ = 0.0;
}

std::optional<StaticMass> StaticInitializer::step(const Sample& sample) {
  const bool usable = sample.has(Input::kSpeed) && sample.has(Input::kRearRightDeflection) &&
                      std::isfinite(sample.rear_right_deflection_m);
  const bool still = usable && std::abs(sample.speed_mps) <= params_.standstill_speed_mps;
  if (!still) {
    standing_ = false;
    restart_window();
    return std::nullopt;
  }
  if (!standing_) {
    standing_ = true;
    standing_since_us_ = sample.time_us;
  }
  if (to_seconds(sample.time_us - standing_since_us_) < params_.settle_s) return std::nullopt;

  if (!window_open_) {
    window_open_ = true;
    window_start_us_ = sample.time_us;
  }
  // Welford's running mean and variance of the deflection over the window.
  ++window_count_;
  const double z = sample.rear_right_deflection_m;
  const double delta = z - window_mean_;
  window_mean_ += delta / static_cast<double>(window_count_);
  window_m2_ += delta * (z - window_mean_);
  if (sample.has(Input::kAccelX) && std::isfinite(sample.accel_x_mps2)) {
    ++grade_count_;
    grade_sum_ += sample.accel_x_mps2;
  }

  if (to_seconds(sample.time_us - window_start_us_) < params_.standstill_window_s) {
    return std::nullopt;
  }
  const double mean = window_mean_;
  const double spread =
      window_count_ > 1 ? std::sqrt(window_m2_ / static_cast<double>(window_count_ - 1)) : 0.0;
  // The grade is known only when a_x was valid over most of the window.
  const double grade = 2 * grade_count_ >= window_count_
                           ? grade_sum_ / static_cast<double>(grade_count_)
                           : std::numeric_limits<double>::quiet_NaN();
  restart_window();
  if (spread > params_.max_deflection_std_m) return std::nullopt;  // not settled: try again

  if (!reference_) {
    reference_ = Reference{mean, spread, grade};
    StaticMass out = static_mass_for(mean, spread);
    out.grade_accel_mps2 = grade;
    out.time_us = sample.time_us;
    return out;
  }
  // Another slope shifts load between the axles: not comparable (NaN compares false: a grade
  // that is unknown on either side does not block the comparison).
  if (std::abs(grade - reference_->grade_accel_mps2) > params_.max_grade_change_mps2) {
    return std::nullopt;
  }
  const double noise = std::max(spread, reference_->deflection_std_m);
  const double threshold = std::max(params_.load_change_sigma * noise, params_.min_load_change_m);
  if (std::abs(mean - reference_->deflection_m) <= threshold) return std::nullopt;

  reference_ = Reference{mean, spread, grade};
  StaticMass out = static_mass_for(mean, spread);
  out.grade_accel_mps2 = grade;
  out.time_us = sample.time_us;
  out.load_changed = true;
  return out;
}

}  // namespace vmass

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
  c.non_negative("prior_std_fraction_of_empty", prior_std_fraction_of_empty);
  c.positive("payload_x_min_fraction", payload_x_min_fraction);
  if (!(payload_x_max_fraction >= payload_x_min_fraction)) {
    c.fail("payload_x_max_fraction", "must be >= payload_x_min_fraction");
  }
  if (!(payload_y_max_fraction >= 0.0 && payload_y_max_fraction < 0.5)) {
    c.fail("payload_y_max_fraction", "must be in [0, 0.5)");
  }
  c.positive("out_of_range_prior_std_kg", out_of_range_prior_std_kg);
  c.positive("no_static_prior_std_kg", no_static_prior_std_kg);
  c.positive("mu_prior_std_n", mu_prior_std_n);
  c.positive("load_change_sigma", load_change_sigma);
  c.non_negative("min_load_change_kg", min_load_change_kg);
  c.non_negative("min_load_change_fraction", min_load_change_fraction);
  c.positive("max_grade_change_mps2", max_grade_change_mps2);
  return c.message();
}

namespace {

constexpr double kMaxStandstillAccelPerG = 0.5;  // a 58 % slope

// E[1/q] and E[1/q^2] of the over-read factor q = (x / l_f)(1 - 2 u), x uniform on
// [a l, b l], u = y / t uniform on [-c, c] (independent), in closed form.
void payload_factor(double lf_over_l, double a, double b, double c, double* mean, double* std) {
  const double e_x = a == b ? lf_over_l / a : lf_over_l * std::log(b / a) / (b - a);
  const double e_x2 = lf_over_l * lf_over_l / (a * b);
  const double e_y = c > 0.0 ? std::log((1.0 + 2.0 * c) / (1.0 - 2.0 * c)) / (4.0 * c) : 1.0;
  const double e_y2 = 1.0 / (1.0 - 4.0 * c * c);
  *mean = e_x * e_y;
  *std = std::sqrt(std::max(0.0, e_x2 * e_y2 - (*mean) * (*mean)));
}

}  // namespace

StaticInitializer::StaticInitializer(const VehicleParams& vehicle,
                                     const SuspensionParams& suspension,
                                     const StaticInitParams& params)
    : vehicle_(vehicle), suspension_(suspension), params_(params) {
  payload_factor(vehicle.cg_to_front_axle_m / vehicle.wheelbase_m, params.payload_x_min_fraction,
                 params.payload_x_max_fraction, params.payload_y_max_fraction, &factor_mean_,
                 &factor_std_);
}

double StaticInitializer::base_std_kg() const {
  return std::max(params_.prior_std_kg,
                  params_.prior_std_fraction_of_empty * vehicle_.empty_mass_kg);
}

double StaticInitializer::mass_from_deflection_kg(double deflection_m) const {
  const double rear_wheel_force_n = suspension_.wheel_force_n(deflection_m);
  return vehicle_.empty_mass_kg + 2.0 * vehicle_.wheelbase_m * rear_wheel_force_n /
                                      (vehicle_.cg_to_front_axle_m * vehicle_.gravity_mps2);
}

StaticMass StaticInitializer::static_mass_for(double deflection_m, double deflection_std_m) const {
  StaticMass out;
  out.deflection_m = deflection_m;
  out.deflection_std_m = deflection_std_m;
  const double eq3_added_kg = mass_from_deflection_kg(deflection_m) - vehicle_.empty_mass_kg;
  // The linear model is trusted up to its linear range, a calibrated progressive curve up to its
  // calibrated range; beyond, the static mass is only a rough start.
  const double trusted_kg =
      suspension_.is_progressive() ? suspension_.calibrated_range_kg : suspension_.linear_range_kg;
  out.beyond_calibrated_range = std::abs(eq3_added_kg) > trusted_kg;
  // Where the payload sits is unknown: eq. (3)'s added mass corrected by E[1/q], its spread by
  // Std[1/q] (see the header).
  out.added_mass_kg = factor_mean_ * eq3_added_kg;
  out.prior.mass_kg = vehicle_.empty_mass_kg + out.added_mass_kg;
  const double in_range_std_kg = std::hypot(base_std_kg(), factor_std_ * eq3_added_kg);
  out.prior.mass_std_kg = out.beyond_calibrated_range
                              ? std::max(params_.out_of_range_prior_std_kg, in_range_std_kg)
                              : in_range_std_kg;
  out.prior.mu_n = 0.0;
  out.prior.mu_std_n = params_.mu_prior_std_n;
  return out;
}

MassPrior StaticInitializer::no_static_prior() const {
  MassPrior p;
  const double capacity_kg = vehicle_.payload_capacity_kg();
  if (capacity_kg > 0.0) {
    // Uniform between empty and fully loaded: mean half the capacity, std capacity / sqrt(12).
    p.mass_kg = vehicle_.empty_mass_kg + 0.5 * capacity_kg;
    p.mass_std_kg = std::hypot(base_std_kg(), capacity_kg / std::sqrt(12.0));
  } else {
    p.mass_kg = vehicle_.empty_mass_kg;
    p.mass_std_kg = std::max(params_.no_static_prior_std_kg, base_std_kg());
  }
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
  if (!suspension_.carries_load()) return std::nullopt;
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
  // At rest a_x is g sin(grade): a reading beyond half a g is a spike, not a slope (one 1e6x
  // spike in the mean would make the next stop read as "another grade").
  if (sample.has(Input::kAccelX) &&
      std::abs(sample.accel_x_mps2) < kMaxStandstillAccelPerG * vehicle_.gravity_mps2) {
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
  return judge_window(sample.time_us, mean, spread, grade);
}

std::optional<StaticMass> StaticInitializer::judge_window(TimeUs time_us, double mean,
                                                          double spread, double grade) {
  if (!reference_) {
    reference_ = Reference{mean, spread, grade};
    StaticMass out = static_mass_for(mean, spread);
    out.grade_accel_mps2 = grade;
    out.time_us = time_us;
    return out;
  }
  // Another slope shifts load between the axles: not comparable (NaN compares false: a grade
  // that is unknown on either side does not block the comparison).
  if (std::abs(grade - reference_->grade_accel_mps2) > params_.max_grade_change_mps2) {
    return std::nullopt;
  }
  // The eq. (3) mass change between the windows against the larger of the floors and the
  // windows' noise (the deflection's spread turned into mass by eq. 3's slope).
  const double eq3_change_kg =
      mass_from_deflection_kg(mean) - mass_from_deflection_kg(reference_->deflection_m);
  const double kg_per_m =
      std::abs(mass_from_deflection_kg(mean + 1e-3) - mass_from_deflection_kg(mean)) * 1e3;
  const double noise_kg = kg_per_m * std::max(spread, reference_->deflection_std_m);
  const double threshold_kg = std::max({params_.min_load_change_kg,
                                        params_.min_load_change_fraction * vehicle_.empty_mass_kg,
                                        params_.load_change_sigma * noise_kg});
  if (std::abs(eq3_change_kg) <= threshold_kg) return std::nullopt;

  reference_ = Reference{mean, spread, grade};
  StaticMass out = static_mass_for(mean, spread);
  out.grade_accel_mps2 = grade;
  out.time_us = time_us;
  out.load_changed = true;
  out.mass_change_kg = factor_mean_ * eq3_change_kg;
  out.mass_change_std_kg = std::hypot(base_std_kg(), factor_std_ * eq3_change_kg);
  return out;
}

}  // namespace vmass

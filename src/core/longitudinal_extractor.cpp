#include "vmass/core/longitudinal_extractor.hpp"

#include <algorithm>
#include <cmath>

#include "vmass/core/param_check.hpp"

namespace vmass {

std::string LongitudinalParams::validate() const {
  ParamCheck c("estimator.longitudinal");
  c.positive("max_abs_accel_y_mps2", max_abs_accel_y_mps2);
  c.non_negative("min_abs_delta_accel_x_mps2", min_abs_delta_accel_x_mps2);
  c.non_negative("min_abs_delta_force_n", min_abs_delta_force_n);
  c.non_negative("min_speed_mps", min_speed_mps);
  c.positive("weight", weight);
  return c.message();
}

LongitudinalExtractor::LongitudinalExtractor(const VehicleParams& vehicle,
                                             const LongitudinalParams& params,
                                             const DifferencingParams& differencing)
    : vehicle_(vehicle),
      params_(params),
      accel_x_filter_(differencing.filter_cutoff_hz, differencing.tick_rate_hz),
      accel_y_filter_(differencing.filter_cutoff_hz, differencing.tick_rate_hz),
      force_filter_(differencing.filter_cutoff_hz, differencing.tick_rate_hz),
      history_(differencing) {}

void LongitudinalExtractor::reset() {
  history_.clear();
  accel_x_filter_.reset();
  accel_y_filter_.reset();
  force_filter_.reset();
}

Extraction LongitudinalExtractor::step(const Sample& s) {
  Extraction out;
  if (!params_.enabled) {
    out.verdict = PairVerdict::kDisabled;
    return out;
  }
  if (!s.has_all(kRequired)) {
    reset();  // a hole in the data: never difference across it
    out.verdict = PairVerdict::kInputsInvalid;
    return out;
  }
  const double force_n = s.wheel_torque_nm / vehicle_.wheel_radius_m -
                         s.brake_pressure_pa * vehicle_.brake_gain_n_per_pa;
  if (!std::isfinite(force_n) || !std::isfinite(s.accel_x_mps2) || !std::isfinite(s.accel_y_mps2) ||
      !std::isfinite(s.speed_mps)) {
    reset();
    out.verdict = PairVerdict::kNonFinite;
    return out;
  }
  if (std::abs(s.speed_mps) < params_.min_speed_mps) {
    // Standing or creeping, the brake model F = K P does not hold (the brakes hold the car with
    // whatever force it takes): restart the filters, so that their memory of standstill does
    // not leak into the first pairs after driving off.
    reset();
    out.verdict = PairVerdict::kSpeed;
    return out;
  }
  const Record now{s.time_us,
                   accel_x_filter_.step(s.accel_x_mps2),
                   accel_y_filter_.step(s.accel_y_mps2),
                   force_filter_.step(force_n),
                   s.speed_mps,
                   s.gear,
                   s.has(Input::kGear)};
  const Record* then_ptr = history_.push_and_get_then(now, &out.verdict);
  if (then_ptr == nullptr) return out;
  const Record& then = *then_ptr;
  if (std::max(std::abs(now.accel_y_mps2), std::abs(then.accel_y_mps2)) >=
      params_.max_abs_accel_y_mps2) {
    out.verdict = PairVerdict::kLateralAccel;
    return out;
  }
  if (now.gear_valid && then.gear_valid && now.gear != then.gear) {
    out.verdict = PairVerdict::kGearChange;
    return out;
  }
  const double delta_accel = now.accel_x_mps2 - then.accel_x_mps2;
  const double delta_force = now.force_n - then.force_n;
  if (std::abs(delta_accel) <= params_.min_abs_delta_accel_x_mps2) {
    out.verdict = PairVerdict::kSmallDeltaAccel;
    return out;
  }
  if (std::abs(delta_force) <= params_.min_abs_delta_force_n) {
    out.verdict = PairVerdict::kSmallDeltaForce;
    return out;
  }
  const double rotating_mass_kg = vehicle_.rotating_mass_for_gear(now.gear, now.gear_valid);
  out.verdict = PairVerdict::kAccepted;
  out.pair.time_us = now.time_us;
  out.pair.block = Block::kLongitudinal;
  out.pair.delta_accel_mps2 = delta_accel;
  out.pair.y_n = delta_force - rotating_mass_kg * delta_accel;
  out.pair.weight = params_.weight;
  return out;
}

}  // namespace vmass

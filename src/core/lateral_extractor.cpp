#include "vmass/core/lateral_extractor.hpp"

#include <algorithm>
#include <cmath>

#include "vmass/core/lateral_forces.hpp"
#include "vmass/core/param_check.hpp"

namespace vmass {
namespace {
constexpr double kDegToRad = 3.14159265358979323846 / 180.0;
}

std::string LateralParams::validate() const {
  ParamCheck c("estimator.lateral");
  c.positive("max_abs_accel_y_mps2", max_abs_accel_y_mps2);
  c.non_negative("min_abs_delta_accel_y_mps2", min_abs_delta_accel_y_mps2);
  c.positive("max_abs_accel_x_mps2", max_abs_accel_x_mps2);
  c.non_negative("min_abs_steering_wheel_angle_deg", min_abs_steering_wheel_angle_deg);
  c.positive("min_speed_mps", min_speed_mps);
  c.positive("weight", weight);
  c.nested(velocity_filter.validate());
  return c.message();
}

LateralExtractor::LateralExtractor(const VehicleParams& vehicle, const LateralParams& params,
                                   const DifferencingParams& differencing)
    : vehicle_(vehicle),
      params_(params),
      tick_us_(from_seconds(1.0 / differencing.tick_rate_hz)),
      velocity_filter_(params.velocity_filter),
      accel_y_filter_(differencing.filter_cutoff_hz, differencing.tick_rate_hz),
      force_filter_(differencing.filter_cutoff_hz, differencing.tick_rate_hz),
      history_(differencing) {}

void LateralExtractor::reset() {
  history_.clear();
  velocity_filter_.reset();
  accel_y_filter_.reset();
  force_filter_.reset();
  has_last_time_ = false;
}

void LateralExtractor::step_velocity_filter(const Sample& s) {
  const double step_s = has_last_time_ ? to_seconds(s.time_us - last_time_us_) : 0.0;
  if (has_last_time_ && !(step_s > 0.0 && step_s < 10.0 * to_seconds(tick_us_))) {
    reset();  // time went backwards or jumped: restart the filter
  }
  velocity_filter_.step(has_last_time_ ? step_s : 0.0, s.accel_x_mps2, s.accel_y_mps2,
                        s.yaw_rate_radps, s.speed_mps);
  has_last_time_ = true;
  last_time_us_ = s.time_us;
}

PairVerdict LateralExtractor::gate(const Record& now, const Record& then) const {
  if (std::max(std::abs(now.accel_y_mps2), std::abs(then.accel_y_mps2)) >=
      params_.max_abs_accel_y_mps2) {
    return PairVerdict::kLateralAccel;
  }
  if (std::max(std::abs(now.accel_x_mps2), std::abs(then.accel_x_mps2)) >=
      params_.max_abs_accel_x_mps2) {
    return PairVerdict::kLongitudinalAccel;
  }
  const double min_steer_rad = params_.min_abs_steering_wheel_angle_deg * kDegToRad;
  if (std::min(std::abs(now.steering_wheel_angle_rad), std::abs(then.steering_wheel_angle_rad)) <=
      min_steer_rad) {
    return PairVerdict::kSteering;
  }
  if (std::abs(now.accel_y_mps2 - then.accel_y_mps2) <= params_.min_abs_delta_accel_y_mps2) {
    return PairVerdict::kSmallDeltaAccel;
  }
  return PairVerdict::kAccepted;
}

Extraction LateralExtractor::step(const Sample& s) {
  Extraction out;
  if (!params_.enabled) {
    out.verdict = PairVerdict::kDisabled;
    return out;
  }
  if (!s.has_all(kRequired)) {
    reset();
    out.verdict = PairVerdict::kInputsInvalid;
    return out;
  }
  if (!std::isfinite(s.accel_x_mps2) || !std::isfinite(s.accel_y_mps2) ||
      !std::isfinite(s.yaw_rate_radps) || !std::isfinite(s.speed_mps) ||
      !std::isfinite(s.steering_wheel_angle_rad)) {
    reset();
    out.verdict = PairVerdict::kNonFinite;
    return out;
  }
  // The velocity filter runs on every valid tick, also below the gates, so that v_y is ready
  // when an event comes.
  step_velocity_filter(s);

  if (std::abs(s.speed_mps) < params_.min_speed_mps) {
    history_.clear();  // slip angles divide by v_x: nothing to difference at low speed
    accel_y_filter_.reset();
    force_filter_.reset();
    out.verdict = PairVerdict::kSpeed;
    return out;
  }
  const double road_wheel_angle_rad = s.steering_wheel_angle_rad / vehicle_.steering_ratio;
  const AxleLateralForces forces =
      axle_lateral_forces(vehicle_, s.speed_mps, velocity_filter_.lateral_velocity_mps(),
                          s.yaw_rate_radps, road_wheel_angle_rad);
  if (!std::isfinite(forces.total_n)) {
    reset();
    out.verdict = PairVerdict::kNonFinite;
    return out;
  }
  const Record now{s.time_us,
                   s.accel_x_mps2,
                   accel_y_filter_.step(s.accel_y_mps2),
                   force_filter_.step(forces.total_n),
                   s.speed_mps,
                   s.steering_wheel_angle_rad};
  const Record* then_ptr = history_.push_and_get_then(now, &out.verdict);
  if (then_ptr == nullptr) return out;
  const Record& then = *then_ptr;
  out.verdict = gate(now, then);  // Table III
  if (out.verdict != PairVerdict::kAccepted) return out;
  out.pair.time_us = now.time_us;
  out.pair.block = Block::kLateral;
  out.pair.delta_accel_mps2 = now.accel_y_mps2 - then.accel_y_mps2;
  out.pair.y_n = now.lateral_force_n - then.lateral_force_n;
  out.pair.weight = params_.weight;
  return out;
}

}  // namespace vmass

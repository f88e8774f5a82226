// LateralExtractor: lateral regression pairs (paper eqs. 8-12, Table III).
//
// Each tick: the LateralVelocityFilter (model 11) gives v_y; the slip angles (12) and axle
// forces (10) give F_lat = F_yf cos(delta_f) + F_yr (see lateral_forces.hpp for the sign
// convention), with delta_f = steering-wheel angle / steering ratio. Differenced over dt,
//   M da_y = dF_lat                                                              eq. (9)
// so the pair is y = dF_lat, phi = [da_y, 1].
//
// Gates (Table III, thresholds from config): |a_y| < max_abs_accel_y_mps2 at both ends,
// |da_y| > min_abs_delta_accel_y_mps2, v_x constant (|a_x| < max_abs_accel_x_mps2 at both ends),
// |steering-wheel angle| > min_abs_steering_wheel_angle_deg at both ends; and speed >=
// min_speed_mps (slip angles divide by v_x), inputs valid and finite, samples dt apart.
// a_y and F_lat are low-pass filtered identically before differencing.
//
// Not thread-safe; allocates only in the constructor.
#pragma once

#include <string>

#include "vmass/core/differencing_history.hpp"
#include "vmass/core/extraction.hpp"
#include "vmass/core/lateral_velocity_filter.hpp"
#include "vmass/core/low_pass_filter.hpp"
#include "vmass/core/sample.hpp"
#include "vmass/core/vehicle_params.hpp"

namespace vmass {

struct LateralParams {
  bool enabled = false;  // off by default: see docs/estimator.md (population suite)
  double max_abs_accel_y_mps2 = 4.0;
  double min_abs_delta_accel_y_mps2 = 0.01;
  double max_abs_accel_x_mps2 = 0.3;
  double min_abs_steering_wheel_angle_deg = 15.0;
  double min_speed_mps = 5.0;
  double weight = 0.5;
  LateralVelocityFilterParams velocity_filter;

  std::string validate() const;
};

class LateralExtractor {
 public:
  LateralExtractor(const VehicleParams& vehicle, const LateralParams& params,
                   const DifferencingParams& differencing);

  Extraction step(const Sample& sample);
  void reset();
  const LateralVelocityFilter& velocity_filter() const { return velocity_filter_; }

  static constexpr InputMask kRequired = input_bit(Input::kAccelX) | input_bit(Input::kAccelY) |
                                         input_bit(Input::kYawRate) | input_bit(Input::kSpeed) |
                                         input_bit(Input::kSteeringWheelAngle);

 private:
  struct Record {
    TimeUs time_us;
    double accel_x_mps2;
    double accel_y_mps2;
    double lateral_force_n;
    double speed_mps;
    double steering_wheel_angle_rad;
  };

  /// The velocity filter's step, restarted when time went backwards or jumped.
  void step_velocity_filter(const Sample& s);
  /// Table III's gates on a pair; kAccepted when it passes them all.
  PairVerdict gate(const Record& now, const Record& then) const;

  VehicleParams vehicle_;
  LateralParams params_;
  TimeUs tick_us_;
  LateralVelocityFilter velocity_filter_;
  LowPassFilter accel_y_filter_, force_filter_;
  DifferencingHistory<Record> history_;
  bool has_last_time_ = false;
  TimeUs last_time_us_ = 0;
};

}  // namespace vmass

// LateralVelocityFilter: a linear Kalman filter on the kinematic model (11) for the lateral
// velocity v_y. It does not depend on the mass.
//
//   d/dt [v_x]   [ 0    r ] [v_x]   [a_x - b_x]
//        [v_y] = [ -r   0 ] [v_y] + [a_y      ]          measured: v_x (wheel speed)
//
// r is the yaw rate, a_x, a_y the measured accelerations (ISO 8855: y left, r positive left).
// Beyond the paper: an accelerometer measures specific force, so on a grade a_x carries
// g sin(grade) (plus the sensor's own offset). Model (11) would read that as r v_y and put an
// error of g sin(grade) / r into v_y, which changes with r through every manoeuvre and biases
// the lateral mass by tens of percent (measured on the simulator's paper_exp2). The filter
// therefore carries the offset b_x as a third state (a random walk) that v_x makes observable.
// v_y itself is observable only while turning; on straight roads it would integrate the lateral
// accelerometer's offset (bank, bias) without bound, so a weak pseudo-measurement v_y = 0 keeps
// it bounded. A slowly varying error in v_y cancels in the differenced slip angles.
//
// Not thread-safe; no allocation.
#pragma once

#include <string>

#include <Eigen/Core>

namespace vmass {

struct LateralVelocityFilterParams {
  double accel_noise_std_mps2 = 0.05;
  double speed_noise_std_mps = 0.05;
  double pseudo_lateral_velocity_std_mps = 10.0;
  double initial_lateral_velocity_std_mps = 0.5;
  double accel_x_offset_walk_mps2_per_sqrt_s = 0.02;  ///< grade changes along the road
  double initial_accel_x_offset_std_mps2 = 0.5;

  std::string validate() const;
};

class LateralVelocityFilter {
 public:
  explicit LateralVelocityFilter(const LateralVelocityFilterParams& params);

  /// Predict over dt_s with the measured accelerations and yaw rate, then update with v_x.
  void step(double dt_s, double accel_x_mps2, double accel_y_mps2, double yaw_rate_radps,
            double speed_mps);
  void reset();
  bool initialised() const { return initialised_; }
  double lateral_velocity_mps() const { return x_(1); }
  double longitudinal_velocity_mps() const { return x_(0); }
  double lateral_velocity_std_mps() const;

 private:
  LateralVelocityFilterParams params_;
  bool initialised_ = false;
  Eigen::Vector3d x_ = Eigen::Vector3d::Zero();  ///< v_x, v_y, b_x
  Eigen::Matrix3d p_ = Eigen::Matrix3d::Identity();
  Eigen::Vector3d last_inputs_ = Eigen::Vector3d::Zero();  ///< a_x, a_y, r of the last step
};

}  // namespace vmass

// LateralVelocityFilter: a linear Kalman filter on the kinematic model (11) for the lateral
// velocity v_y. It does not depend on the mass.
//
//   d/dt [v_x]   [ 0    r ] [v_x]   [a_x]
//        [v_y] = [ -r   0 ] [v_y] + [a_y]          measured: v_x (wheel speed)
//
// r is the yaw rate, a_x, a_y the measured specific forces (ISO 8855: y left, r positive left).
// The transition over a step h is the exact rotation by -r h plus the integrated accelerations.
// v_y is observable only while turning (through dv_x/dt = a_x + r v_y); on straight roads it
// would integrate the accelerometer bias without bound, so a weak pseudo-measurement v_y = 0
// (std pseudo_lateral_velocity_std_mps) keeps it bounded. The extractor differences slip angles
// over dt, so a slowly varying error in v_y cancels.
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
  Eigen::Vector2d x_ = Eigen::Vector2d::Zero();
  Eigen::Matrix2d p_ = Eigen::Matrix2d::Identity();
  Eigen::Vector3d last_inputs_ = Eigen::Vector3d::Zero();  ///< a_x, a_y, r of the last step
};

}  // namespace vmass

#include "vmass/core/lateral_velocity_filter.hpp"

#include <cmath>

#include <Eigen/LU>

#include "vmass/core/param_check.hpp"

namespace vmass {

std::string LateralVelocityFilterParams::validate() const {
  ParamCheck c("estimator.lateral.velocity_filter");
  c.positive("accel_noise_std_mps2", accel_noise_std_mps2);
  c.positive("speed_noise_std_mps", speed_noise_std_mps);
  c.positive("pseudo_lateral_velocity_std_mps", pseudo_lateral_velocity_std_mps);
  c.positive("initial_lateral_velocity_std_mps", initial_lateral_velocity_std_mps);
  return c.message();
}

LateralVelocityFilter::LateralVelocityFilter(const LateralVelocityFilterParams& params)
    : params_(params) {}

void LateralVelocityFilter::reset() { initialised_ = false; }

double LateralVelocityFilter::lateral_velocity_std_mps() const { return std::sqrt(p_(1, 1)); }

void LateralVelocityFilter::step(double dt_s, double accel_x_mps2, double accel_y_mps2,
                                 double yaw_rate_radps, double speed_mps) {
  if (!initialised_) {
    x_ << speed_mps, 0.0;
    p_.setZero();
    p_(0, 0) = params_.speed_noise_std_mps * params_.speed_noise_std_mps;
    p_(1, 1) = params_.initial_lateral_velocity_std_mps * params_.initial_lateral_velocity_std_mps;
    initialised_ = true;
    return;
  }
  // Predict: exact solution of the linear ODE over dt with the inputs held constant.
  const double angle = yaw_rate_radps * dt_s;
  const double c = std::cos(angle);
  const double s = std::sin(angle);
  Eigen::Matrix2d f;
  f << c, s, -s, c;
  x_ = f * x_ + Eigen::Vector2d(accel_x_mps2, accel_y_mps2) * dt_s;
  const double q = params_.accel_noise_std_mps2 * dt_s;
  p_ = f * p_ * f.transpose();
  p_(0, 0) += q * q;
  p_(1, 1) += q * q;

  // Update with z = [v_x measured, 0 (pseudo-measurement of v_y)], H = I.
  Eigen::Matrix2d r = Eigen::Matrix2d::Zero();
  r(0, 0) = params_.speed_noise_std_mps * params_.speed_noise_std_mps;
  r(1, 1) = params_.pseudo_lateral_velocity_std_mps * params_.pseudo_lateral_velocity_std_mps;
  const Eigen::Matrix2d innovation_cov = p_ + r;
  const Eigen::Matrix2d gain = p_ * innovation_cov.inverse();
  const Eigen::Vector2d innovation(speed_mps - x_(0), -x_(1));
  x_ += gain * innovation;
  const Eigen::Matrix2d i_kh = Eigen::Matrix2d::Identity() - gain;
  p_ = i_kh * p_ * i_kh.transpose() + gain * r * gain.transpose();  // Joseph form
  p_ = 0.5 * (p_ + p_.transpose());
}

}  // namespace vmass

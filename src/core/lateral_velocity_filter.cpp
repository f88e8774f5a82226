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
  c.positive("accel_x_offset_walk_mps2_per_sqrt_s", accel_x_offset_walk_mps2_per_sqrt_s);
  c.positive("initial_accel_x_offset_std_mps2", initial_accel_x_offset_std_mps2);
  return c.message();
}

LateralVelocityFilter::LateralVelocityFilter(const LateralVelocityFilterParams& params)
    : params_(params) {}

void LateralVelocityFilter::reset() { initialised_ = false; }

double LateralVelocityFilter::lateral_velocity_std_mps() const { return std::sqrt(p_(1, 1)); }

void LateralVelocityFilter::step(double dt_s, double accel_x_mps2, double accel_y_mps2,
                                 double yaw_rate_radps, double speed_mps) {
  const Eigen::Vector3d inputs(accel_x_mps2, accel_y_mps2, yaw_rate_radps);
  if (!initialised_) {
    x_ << speed_mps, 0.0, 0.0;
    p_.setZero();
    p_(0, 0) = params_.speed_noise_std_mps * params_.speed_noise_std_mps;
    p_(1, 1) = params_.initial_lateral_velocity_std_mps * params_.initial_lateral_velocity_std_mps;
    p_(2, 2) = params_.initial_accel_x_offset_std_mps2 * params_.initial_accel_x_offset_std_mps2;
    initialised_ = true;
    last_inputs_ = inputs;
    return;
  }
  // x = [v_x, v_y, b_x]; x' = A(r) x + u with
  //   A = [[0, r, -1], [-r, 0, 0], [0, 0, 0]],  u = [a_x, a_y, 0].
  // Trapezoidal (Crank-Nicolson) rule: (I - h/2 A1) x1 = (I + h/2 A0) x0 + h/2 (u0 + u1).
  // It is exact for the kinematic identity dv_x/dt = a_x - b_x + r v_y at both ends of the step;
  // holding the first sample's inputs instead makes the v_x innovations drag v_y half a step
  // behind, which biases the differenced slip angles (and so the mass) by about 0.6%.
  const double h2 = 0.5 * dt_s;
  auto transition = [](double r) {
    Eigen::Matrix3d a = Eigen::Matrix3d::Zero();
    a(0, 1) = r;
    a(0, 2) = -1.0;
    a(1, 0) = -r;
    return a;
  };
  const Eigen::Matrix3d forward = Eigen::Matrix3d::Identity() + h2 * transition(last_inputs_(2));
  const Eigen::Matrix3d backward = Eigen::Matrix3d::Identity() - h2 * transition(inputs(2));
  const Eigen::Matrix3d backward_inv = backward.inverse();  // det = 1 + (h r / 2)^2 > 0
  const Eigen::Matrix3d f = backward_inv * forward;
  Eigen::Vector3d u = Eigen::Vector3d::Zero();
  u.head<2>() = h2 * (last_inputs_.head<2>() + inputs.head<2>());
  x_ = f * x_ + backward_inv * u;
  last_inputs_ = inputs;

  const double q = params_.accel_noise_std_mps2 * dt_s;
  const double walk = params_.accel_x_offset_walk_mps2_per_sqrt_s;
  p_ = f * p_ * f.transpose();
  p_(0, 0) += q * q;
  p_(1, 1) += q * q;
  p_(2, 2) += walk * walk * dt_s;

  // Update with z = [v_x measured, 0 (pseudo-measurement of v_y)].
  Eigen::Matrix<double, 2, 3> h = Eigen::Matrix<double, 2, 3>::Zero();
  h(0, 0) = 1.0;
  h(1, 1) = 1.0;
  Eigen::Matrix2d r = Eigen::Matrix2d::Zero();
  r(0, 0) = params_.speed_noise_std_mps * params_.speed_noise_std_mps;
  r(1, 1) = params_.pseudo_lateral_velocity_std_mps * params_.pseudo_lateral_velocity_std_mps;
  const Eigen::Matrix2d innovation_cov = h * p_ * h.transpose() + r;
  const Eigen::Matrix<double, 3, 2> gain = p_ * h.transpose() * innovation_cov.inverse();
  const Eigen::Vector2d innovation(speed_mps - x_(0), -x_(1));
  x_ += gain * innovation;
  const Eigen::Matrix3d i_kh = Eigen::Matrix3d::Identity() - gain * h;
  p_ = i_kh * p_ * i_kh.transpose() + gain * r * gain.transpose();  // Joseph form
  p_ = 0.5 * (p_ + p_.transpose());
}

}  // namespace vmass

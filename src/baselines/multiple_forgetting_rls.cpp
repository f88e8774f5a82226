#include "vmass/baselines/multiple_forgetting_rls.hpp"

#include <cmath>

namespace vmass::baselines {

MultipleForgettingRls::MultipleForgettingRls(const Eigen::Vector2d& theta0,
                                             const Eigen::Vector2d& prior_std,
                                             const MultipleForgettingRlsParams& params)
    : params_(params),
      inflation_(1.0 / std::sqrt(params.forgetting_1), 1.0 / std::sqrt(params.forgetting_2)),
      theta_(theta0) {
  p_ = prior_std.cwiseProduct(prior_std).asDiagonal();
}

bool MultipleForgettingRls::update(double y, double phi_1, double phi_2) {
  if (!std::isfinite(y) || !std::isfinite(phi_1) || !std::isfinite(phi_2)) return false;
  const Eigen::RowVector2d phi(phi_1, phi_2);
  Eigen::Matrix2d prior = inflation_.asDiagonal() * p_ * inflation_.asDiagonal();
  if (!params_.cross_covariance) prior = Eigen::Matrix2d(prior.diagonal().asDiagonal());
  const double s = params_.noise_var + (phi * prior * phi.transpose())(0, 0);
  const Eigen::Vector2d gain = prior * phi.transpose() / s;
  const Eigen::Vector2d theta = theta_ + gain * (y - (phi * theta_)(0, 0));
  Eigen::Matrix2d p = prior - gain * (phi * prior);
  if (params_.cross_covariance) {
    p = 0.5 * (p + p.transpose()).eval();
  } else {
    p = Eigen::Matrix2d(p.diagonal().asDiagonal());  // separate P_1, P_2: (1 - L_i phi_i) P_i
  }
  if (!theta.allFinite() || !p.allFinite() || !(p(0, 0) > 0.0) || !(p(1, 1) > 0.0)) return false;
  theta_ = theta;
  p_ = p;
  ++updates_;
  return true;
}

}  // namespace vmass::baselines

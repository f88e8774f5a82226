#include "vmass/baselines/paper_rls.hpp"

#include <cmath>

namespace vmass::baselines {

PaperRls::PaperRls(double noise_std_n, const Eigen::Vector2d& theta0,
                   const Eigen::Vector2d& prior_std)
    : noise_var_(noise_std_n * noise_std_n), theta_(theta0) {
  p_ = prior_std.cwiseProduct(prior_std).asDiagonal();
}

bool PaperRls::update(double y, const Eigen::RowVector2d& phi) {
  if (!std::isfinite(y) || !phi.allFinite()) return false;
  const double s = (phi * p_ * phi.transpose())(0, 0) + noise_var_;
  const Eigen::Vector2d k = p_ * phi.transpose() / s;
  const Eigen::Vector2d theta = theta_ + k * (y - (phi * theta_)(0, 0));
  const Eigen::Matrix2d a = Eigen::Matrix2d::Identity() - k * phi;
  Eigen::Matrix2d p = a * p_ * a.transpose() + noise_var_ * k * k.transpose();
  p = 0.5 * (p + p.transpose()).eval();
  if (!theta.allFinite() || !p.allFinite()) return false;
  theta_ = theta;
  p_ = p;
  ++updates_;
  return true;
}

}  // namespace vmass::baselines

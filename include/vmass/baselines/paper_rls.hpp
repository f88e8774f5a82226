// PaperRls: the paper's recursive least squares on theta = [M, mu] (El Mrhasli et al., eqs.
// 14-16), with the standard measurement-noise term r = noise_std_n^2 that eq. (15) as printed
// lacks (without it, K phi = 1 after the first pair and P becomes singular):
//   S     = phi P phi^T + r
//   K     = P phi^T / S                                   eq. (15) + r
//   theta = theta + K (y - phi theta)                     eq. (14)
//   P     = (I - K phi) P (I - K phi)^T + K r K^T         eq. (16) + r (Joseph form)
// No forgetting, no bounds, no gate on the innovation (the paper has none). Started at
// theta0 with P0 = diag(sigma_M^2, sigma_mu^2), it is the regularised batch least-squares
// solution argmin (theta - theta0)^T P0^-1 (theta - theta0) + sum (y_i - phi_i theta)^2 / r.
// An update with a non-finite field, or one whose result is not finite, changes nothing.
// Independent of vmass::RlsEstimator on purpose: a baseline must not move when the product does.
// Not thread-safe; no allocation.
#pragma once

#include <Eigen/Core>

namespace vmass::baselines {

class PaperRls {
 public:
  /// noise_std_n > 0; prior standard deviations > 0.
  PaperRls(double noise_std_n, const Eigen::Vector2d& theta0, const Eigen::Vector2d& prior_std);

  /// One pair y = phi theta + e. Returns whether the state changed.
  bool update(double y, const Eigen::RowVector2d& phi);

  const Eigen::Vector2d& theta() const { return theta_; }
  const Eigen::Matrix2d& covariance() const { return p_; }
  long updates() const { return updates_; }

 private:
  double noise_var_;
  Eigen::Vector2d theta_;
  Eigen::Matrix2d p_;
  long updates_ = 0;
};

}  // namespace vmass::baselines

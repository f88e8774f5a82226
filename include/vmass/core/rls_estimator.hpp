// RlsEstimator: recursive least squares on theta = [M, mu] (paper eqs. 14-16), in the standard
// form with a measurement-noise variance, an optional forgetting factor, and a covariance that is
// kept symmetric positive definite and bounded.
//
// For an accepted pair (y, phi = [da, 1], weight w), with r = noise_std_n^2 / w:
//   S     = phi P phi^T + r                     innovation variance
//   K     = P phi^T / S                         gain (eq. 15 with the noise term the paper omits)
//   theta = theta + K (y - phi theta)           eq. 14
//   P     = ((I - K phi) P (I - K phi)^T + K r K^T) / lambda      Joseph form (eq. 16 plus noise)
// then P is symmetrised and its eigenvalues clipped to [min_variance, the prior's variance]
// (per parameter), so that forgetting cannot wind P up during long stretches without
// excitation, and rounding cannot make it indefinite. Without forgetting (lambda = 1) and with
// the bound inactive, the estimate equals the regularised batch least-squares solution
//   argmin (theta - theta0)^T P0^-1 (theta - theta0) + sum_i w_i (y_i - phi_i theta)^2 / sigma^2.
// The published interval is theta_M +/- 1.96 sqrt(P_MM) (Gaussian).
//
// Not thread-safe; no allocation.
#pragma once

#include <string>

#include <Eigen/Core>

#include "vmass/core/mass_regressor.hpp"

namespace vmass {

struct RlsParams {
  double noise_std_n = 100.0;       ///< sigma of y for weight 1, N (> 0)
  double forgetting_factor = 1.0;   ///< lambda in (0.9, 1]; 1 = no forgetting
  double min_variance_fraction = 1e-12;  ///< lower eigenvalue bound, as a fraction of the prior's

  /// Empty when valid, else a message naming the key and the violated bound.
  std::string validate() const;
};

class RlsEstimator final : public MassRegressor {
 public:
  explicit RlsEstimator(const RlsParams& params);

  void reset(const MassPrior& prior) override;
  PairPrediction predict(const RegressionPair& pair) const override;
  bool update(const RegressionPair& pair) override;
  RegressorState state() const override;
  std::string_view name() const override { return "rls"; }

  const Eigen::Vector2d& theta() const { return theta_; }
  const Eigen::Matrix2d& covariance() const { return p_; }
  /// Restore a saved state (persistence); P must be symmetric positive definite.
  void restore(const Eigen::Vector2d& theta, const Eigen::Matrix2d& p, long pairs_used);

 private:
  RlsParams params_;
  Eigen::Vector2d theta_ = Eigen::Vector2d::Zero();
  Eigen::Matrix2d p_ = Eigen::Matrix2d::Identity();
  Eigen::Matrix2d p_max_ = Eigen::Matrix2d::Identity();  ///< the prior's covariance (the bound)
  long pairs_used_ = 0;
};

}  // namespace vmass

// RlsEstimator: recursive least squares on theta = [M, mu] (paper eqs. 14-16), in the standard
// form with a measurement-noise variance, an optional forgetting factor, and a covariance that is
// kept symmetric positive definite and bounded.
//
// For an accepted pair (y, phi = [da, 1], weight w), with r = noise_std_n^2 / w:
//   S     = phi P phi^T + r                     innovation variance
//   K     = P phi^T / S                         gain (eq. 15 with the noise term the paper omits)
//   theta = theta + K (y - phi theta)           eq. 14
//   P     = ((I - K phi) P (I - K phi)^T + K r K^T) / lambda      Joseph form (eq. 16 plus noise)
// then P is symmetrised and bounded between the prior's covariance P0 = diag(sigma_M^2,
// sigma_mu^2) and min_variance_fraction * P0 in the matrix sense: with D = P0^(1/2), the
// eigenvalues of D^-1 P D^-1 are clipped to [min_variance_fraction, 1] (P is left untouched when
// they already lie inside). Working in these prior-whitened coordinates makes the bound
// independent of the units of M and mu, so forgetting cannot wind P up past the prior during
// long stretches without excitation (the unexcited direction saturates at the prior's
// uncertainty) and rounding cannot make P indefinite.
// Without forgetting (lambda = 1) P only shrinks, the upper bound is never active, and (with the
// lower bound inactive) the estimate equals the regularised batch least-squares solution
//   argmin (theta - theta0)^T P0^-1 (theta - theta0) + sum_i w_i (y_i - phi_i theta)^2 / sigma^2
// with P = (P0^-1 + sum_i w_i phi_i^T phi_i / sigma^2)^-1. With forgetting and the bound
// inactive, after N pairs it is the exponentially weighted solution
//   argmin lambda^N (theta - theta0)^T P0^-1 (theta - theta0)
//          + sum_i lambda^(N-i+1) w_i (y_i - phi_i theta)^2 / sigma^2,
// P^-1 being that cost's Hessian / 2 (the information of pair i is discounted from its own step).
// The published interval is theta_M -/+ z sqrt(P_MM) with z = the standard normal 0.975 quantile
// (Boost.Math, 1.959963985...).
//
// Bad data never produces NaN: update() ignores (returns false, changes nothing) a pair with a
// non-finite field or weight <= 0, and an update whose result would not be finite; predict() of
// such a pair returns an infinite variance (and y_n = 0 when phi * theta is not finite).
//
// Not thread-safe; no allocation.
#pragma once

#include <string>

#include <Eigen/Core>

#include "vmass/core/mass_regressor.hpp"

namespace vmass {

struct RlsParams {
  double noise_std_n = 100.0;            ///< sigma of y for weight 1, N (> 0)
  double forgetting_factor = 1.0;        ///< lambda in (0.9, 1]; 1 = no forgetting
  double min_variance_fraction = 1e-12;  ///< lower eigenvalue bound, fraction of P0, in (0, 1)

  /// Empty when valid, else a message naming the key and the violated bound.
  std::string validate() const;
};

class RlsEstimator final : public MassRegressor {
 public:
  /// params must be valid (see RlsParams::validate). Until reset() the prior is theta = 0,
  /// P = I.
  explicit RlsEstimator(const RlsParams& params);

  void reset(const MassPrior& prior) override;
  PairPrediction predict(const RegressionPair& pair) const override;
  bool update(const RegressionPair& pair) override;
  /// Every pair enters the estimate in update(): nothing to flush.
  bool flush() override { return false; }
  RegressorState state() const override;
  std::string_view name() const override { return "rls"; }

  const Eigen::Vector2d& theta() const { return theta_; }
  const Eigen::Matrix2d& covariance() const { return p_; }
  /// The bound P0 set by the last reset().
  const Eigen::Matrix2d& covariance_bound() const { return p_max_; }
  /// Restore a saved state (persistence), after reset() with the prior that set the bound. P must
  /// be finite and symmetric positive definite (it is then clipped to the bound like after an
  /// update); otherwise returns false and changes nothing.
  bool restore(const Eigen::Vector2d& theta, const Eigen::Matrix2d& p, long pairs_used);

 private:
  /// Symmetrise p and clip it to the bound (see the header comment).
  void condition(Eigen::Matrix2d& p) const;

  RlsParams params_;
  double noise_var_n2_ = 1.0;  ///< noise_std_n^2
  double z_ = 0.0;             ///< standard normal 0.975 quantile
  Eigen::Vector2d theta_ = Eigen::Vector2d::Zero();
  Eigen::Matrix2d p_ = Eigen::Matrix2d::Identity();
  Eigen::Matrix2d p_max_ = Eigen::Matrix2d::Identity();  ///< the prior's covariance (the bound)
  long pairs_used_ = 0;
};

}  // namespace vmass

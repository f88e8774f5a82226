// NigRegression: Bayesian linear regression on theta = [M, mu] with the normal-inverse-gamma
// conjugate prior, updated in batches (prior-recursive: each batch's posterior is the next
// batch's prior), as the paper's second observer (eq. 17) and the "plain re-implementation" of
// issue 8 use it. Independent of vmass::BayesEstimator on purpose.
//
// Model: y_i = phi_i theta + e_i, e_i ~ N(0, sigma^2), sigma^2 unknown.
// Prior: theta | sigma^2 ~ N(m0, sigma^2 V0), sigma^2 ~ InvGamma(a0, b0).
// A batch of n pairs, with residuals about the prior mean e_i = y_i - phi_i m0, g = Phi^T e:
//   Vn^-1 = V0^-1 + Phi^T Phi
//   mn    = m0 + Vn g
//   an    = a0 + n / 2
//   bn    = b0 + (e^T e - g^T Vn g) / 2
// (the usual formulas written about m0, which avoids the cancellation of raw y^T y on long runs).
// The marginal of M is Student-t with 2 an degrees of freedom, location mn[0] and scale
// sqrt(bn / an * Vn(0,0)); the interval is its central 95 % interval (Boost.Math quantile).
// Prior from a guess: V0 = diag(sigma_M^2, sigma_mu^2) / s^2, a0 = dof / 2, b0 = a0 s^2, so that
// E[1 / sigma^2] = 1 / s^2 and the prior's t scale for M is sigma_M.
// The published posterior changes only when a batch completes; a batch whose posterior would not
// be finite is dropped. Not thread-safe; no allocation.
#pragma once

#include <Eigen/Core>

namespace vmass::baselines {

struct NigPrior {
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  Eigen::Vector2d std = Eigen::Vector2d::Ones();  ///< sigma_M, sigma_mu
  double noise_std_guess = 1.0;                   ///< s
  double noise_dof = 1.0;                         ///< 2 a0 (> 0)
};

class NigRegression {
 public:
  /// batch_size >= 1; prior std, noise guess and dof > 0.
  NigRegression(const NigPrior& prior, int batch_size);

  /// Add a pair to the open batch; returns whether a batch completed (the posterior changed).
  bool add(double y, const Eigen::RowVector2d& phi);

  const Eigen::Vector2d& mean() const { return mean_; }
  /// Central credible interval of M at `level` (0..1), from the posterior of completed batches.
  void mass_interval(double level, double* low, double* high) const;
  long pairs_used() const { return pairs_used_; }
  long batches() const { return batches_; }

 private:
  void close_batch();

  int batch_size_;
  Eigen::Vector2d mean_;
  Eigen::Matrix2d v_;  ///< V
  double shape_;       ///< a
  double scale_;       ///< b
  // The open batch, about mean_: Phi^T Phi, Phi^T e, e^T e, n.
  Eigen::Matrix2d phi_t_phi_ = Eigen::Matrix2d::Zero();
  Eigen::Vector2d phi_t_e_ = Eigen::Vector2d::Zero();
  double e_t_e_ = 0.0;
  int pending_ = 0;
  long pairs_used_ = 0;
  long batches_ = 0;
};

}  // namespace vmass::baselines

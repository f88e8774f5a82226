// MultipleForgettingRls: recursive least squares with one forgetting factor per parameter, for
// y = phi_1 theta_1 + phi_2 theta_2 + e with two parameters that change at different rates
// (Vahidi, Stefanopoulou & Peng 2005: theta_1 = 1/M is piecewise constant, theta_2 =
// sin(beta + beta_mu) follows the road). Written in the Kalman form of RLS with a measurement
// noise variance r (r = 1 in the normalised textbook form; scaling r and P_0 together leaves theta
// unchanged). Each parameter's uncertainty is inflated by its own factor, then the sample is
// taken in:
//   P-    = D P D,  D = diag(1 / sqrt(lambda_1), 1 / sqrt(lambda_2))     forgetting per parameter
//   S     = r + phi P- phi^T
//   L     = P- phi^T / S
//   theta = theta + L (y - phi theta)
//   P     = P- - L phi P-
// With lambda_1 = lambda_2 = lambda this is exactly RLS with the forgetting factor lambda.
//
// Two forms, chosen by `cross_covariance`:
// - true (default), "vector-type forgetting": P is the full 2 x 2 covariance.
// - false, the paper's separate estimators: P stays diagonal (P_1, P_2, as if each parameter had
//   its own RLS), so L_i = P_i phi_i / (r + phi_1^2 P_1 + phi_2^2 P_2). The paper derives one RLS
//   per parameter, each with its own denominator lambda_i + phi_i^2 P_i; run together, each then
//   corrects the whole prediction error by itself and the two corrections overshoot; its "ad hoc
//   modification of the update law for the gain" shares the denominator, which is this form.
//   ASSUMPTION: the exact printed form of that modification could not be checked against a
//   public copy of the paper. Dropping the cross-covariance makes this form slow: when phi_1 has a
//   large mean (a traction force always present), the fast-forgetting grade absorbs the mass
//   error and theta_1 learns only from the variations of phi_1 (the tests show the bias on
//   noiseless data). Vahidi2005Baseline therefore uses the full form, which the diagonal one
//   approximates and which reproduces the accuracy the paper reports.
//
// An update with a non-finite field, or whose result is not finite, changes nothing.
// Not thread-safe; no allocation.
#pragma once

#include <Eigen/Core>

namespace vmass::baselines {

struct MultipleForgettingRlsParams {
  double forgetting_1 = 1.0;  ///< lambda_1 in (0, 1]
  double forgetting_2 = 1.0;  ///< lambda_2 in (0, 1]
  double noise_var = 1.0;     ///< r > 0
  bool cross_covariance = true;
};

class MultipleForgettingRls {
 public:
  /// theta0 the start, prior_std the standard deviations of its two parameters (> 0).
  MultipleForgettingRls(const Eigen::Vector2d& theta0, const Eigen::Vector2d& prior_std,
                        const MultipleForgettingRlsParams& params);

  /// One sample. Returns whether the state changed.
  bool update(double y, double phi_1, double phi_2);

  const Eigen::Vector2d& theta() const { return theta_; }
  const Eigen::Matrix2d& covariance() const { return p_; }
  long updates() const { return updates_; }

 private:
  MultipleForgettingRlsParams params_;
  Eigen::Vector2d inflation_;  ///< 1 / sqrt(lambda_i)
  Eigen::Vector2d theta_;
  Eigen::Matrix2d p_;
  long updates_ = 0;
};

}  // namespace vmass::baselines

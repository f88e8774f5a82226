// BayesEstimator: prior-recursive Bayesian inference on theta = [M, mu] with the
// normal-inverse-gamma (NIG) conjugate model (paper eq. 17, Step 1/Step 2).
//
// Model: y_i = phi_i theta + e_i, e_i ~ N(0, sigma^2 / w_i), with sigma^2 unknown.
// Prior:  theta | sigma^2 ~ N(m0, sigma^2 V0),  sigma^2 ~ InvGamma(a0, b0).
// Posterior after a batch of n pairs (Phi rows phi_i, W = diag(w_i)):
//   Vn^-1 = V0^-1 + Phi^T W Phi
//   mn    = Vn (V0^-1 m0 + Phi^T W y)
//   an    = a0 + n / 2
//   bn    = b0 + (y^T W y + m0^T V0^-1 m0 - mn^T Vn^-1 mn) / 2
// and the posterior becomes the prior of the next batch. Because the model is conjugate, k
// batches give exactly the posterior of one batch over all their pairs.
// The marginal of M is Student-t with 2 an degrees of freedom, location mn[0] and scale
// sqrt(bn / an * Vn(0,0)); the published interval is its 95% credible interval, from the real
// t quantile (Boost.Math), and mass_std_kg is that marginal's standard deviation (finite once
// 2 an > 2).
//
// The prior is built from a MassPrior and a guess of sigma: E[sigma^2] = noise_std_guess_n^2
// with prior_noise_dof pseudo-observations of confidence, and V0 chosen so that the marginal
// standard deviations of M and mu match the MassPrior's.
//
// Pairs are collected into batches of batch_size (paper: 100 in simulation, 200 on the car);
// the published state changes only when a batch completes. predict() uses the current posterior
// (the pairs of the open batch not yet included).
//
// Not thread-safe; no allocation after construction.
#pragma once

#include <string>

#include <Eigen/Core>

#include "vmass/core/mass_regressor.hpp"

namespace vmass {

struct BayesParams {
  int batch_size = 100;              ///< pairs per posterior update (>= 1)
  double noise_std_guess_n = 100.0;  ///< prior guess of sigma for weight 1, N (> 0)
  double prior_noise_dof = 4.0;      ///< 2 a0: confidence in that guess, pseudo-observations (> 0)
  double credible_level = 0.95;      ///< in (0, 1)

  std::string validate() const;
};

/// The NIG parameters (m, V, a, b), exposed for tests and persistence.
struct NigPosterior {
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  Eigen::Matrix2d scaled_covariance = Eigen::Matrix2d::Identity();  ///< V
  double shape = 1.0;   ///< a
  double scale = 1.0;   ///< b
};

class BayesEstimator final : public MassRegressor {
 public:
  explicit BayesEstimator(const BayesParams& params);

  void reset(const MassPrior& prior) override;
  PairPrediction predict(const RegressionPair& pair) const override;
  bool update(const RegressionPair& pair) override;
  RegressorState state() const override;
  std::string_view name() const override { return "bayes"; }

  const NigPosterior& posterior() const { return posterior_; }
  int pending_pairs() const { return pending_count_; }
  /// Restore a saved posterior (persistence); the open batch starts empty.
  void restore(const NigPosterior& posterior, long pairs_used);

  /// One conjugate update of `prior` by the sufficient statistics of a set of pairs.
  /// Exposed so tests can compare k sequential batches with one batch over all the data.
  struct Sufficient {
    Eigen::Matrix2d phi_t_w_phi = Eigen::Matrix2d::Zero();
    Eigen::Vector2d phi_t_w_y = Eigen::Vector2d::Zero();
    double y_t_w_y = 0.0;
    int count = 0;
    void add(const RegressionPair& pair);
  };
  static NigPosterior conjugate_update(const NigPosterior& prior, const Sufficient& batch);

 private:
  BayesParams params_;
  NigPosterior posterior_;
  Sufficient pending_;
  int pending_count_ = 0;
  long pairs_used_ = 0;
};

}  // namespace vmass

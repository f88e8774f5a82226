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
// batches give exactly the posterior of one batch over all their pairs. (Computed in shifted
// coordinates, see Sufficient::origin, and with V0^-1 m0 etc. from LDLT solves, never from
// explicit inverses; V is kept exactly symmetric.)
// The marginal of theta is a bivariate Student-t with 2 an degrees of freedom, location mn and
// scale matrix bn / an * Vn (its covariance is bn / (an - 1) * Vn when an > 1). The marginal of
// M is Student-t with 2 an dof, location mn[0] and scale sqrt(bn / an * Vn(0,0)); the published
// interval is its central credible_level interval, from the real t quantile (Boost.Math).
// mass_std_kg / mu_std_n are the marginal standard deviations sqrt(bn / (an - 1) * Vn(i,i))
// when an > 1; for an <= 1 the variance is infinite and they report the t scale
// sqrt(bn / an * Vn(i,i)) instead. noise_std_n is sqrt(E[sigma^2]) = sqrt(bn / (an - 1)) when
// an > 1, else sqrt(bn / an).
//
// Prior from a MassPrior (reset), with s = noise_std_guess_n and a0 = prior_noise_dof / 2:
//   b0 = (a0 - 1) s^2   when a0 > 1, so that E[sigma^2] = b0 / (a0 - 1) = s^2;
//   b0 = a0 s^2         when a0 <= 1 (E[sigma^2] is infinite; sigma^2 is then the scaled
//                       inverse chi^2 with 2 a0 dof and scale s^2, i.e. E[1/sigma^2] = 1/s^2);
//   V0 = diag(mass_std_kg^2, mu_std_n^2) / s^2,   m0 = [mass_kg, mu_n].
// With a0 > 1 this makes the marginal variance of theta, b0 / (a0 - 1) V0, equal the MassPrior's
// variances; with a0 <= 1 (infinite variance) it makes the t scale^2, b0 / a0 V0, equal them.
// In both cases the prior predictive noise term (below) is s^2 / w.
//
// predict(): the predictive of y for phi (weight w) is Student-t with 2 an dof, location phi mn
// and scale^2 c = bn / an * (1 / w + phi Vn phi^T). Its variance, returned when an > 1, is
// bn / (an - 1) * (1 / w + phi Vn phi^T). When an <= 1 the variance is infinite and predict()
// returns the Gaussian-equivalent variance c * (t_q / z_q)^2, q = (1 + credible_level) / 2: the
// normal with that variance has the same central credible_level interval as the predictive t.
//
// Pairs are collected into batches of batch_size (paper: 100 in simulation, 200 on the car);
// the published state changes only when a batch completes, or when flush() closes the open
// batch early (end of a log, daemon shutdown; conjugacy makes a short batch exact too). predict()
// uses the current posterior (the pairs of the open batch not yet included).
//
// Bad data never produces NaN: update() ignores (returns false, changes nothing) a pair with a
// non-finite field or weight <= 0; a batch whose posterior would not be finite is dropped.
// predict() of such a pair returns an infinite variance.
//
// The t quantile is looked up in a StudentTQuantiles that copies of the estimator share (the
// pipeline closes the open batch in a copy every tick): each dof is evaluated once.
//
// Not thread-safe (copies share the quantile memo: keep them on one thread); no allocation
// after construction (which allocates the memo).
#pragma once

#include <memory>
#include <string>

#include <Eigen/Core>

#include "vmass/core/mass_regressor.hpp"
#include "vmass/core/student_t_quantiles.hpp"

namespace vmass {

struct BayesParams {
  int batch_size = 100;              ///< pairs per posterior update (>= 1)
  double noise_std_guess_n = 100.0;  ///< prior guess of sigma for weight 1, N (> 0)
  double prior_noise_dof = 4.0;      ///< 2 a0: confidence in that guess, pseudo-observations (> 0)
  double credible_level = 0.95;      ///< in (0, 1)

  /// Empty when valid, else a message naming the key and the violated bound.
  std::string validate() const;
};

/// The NIG parameters (m, V, a, b), exposed for tests and persistence.
struct NigPosterior {
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  Eigen::Matrix2d scaled_covariance = Eigen::Matrix2d::Identity();  ///< V
  double shape = 1.0;                                               ///< a
  double scale = 1.0;                                               ///< b
};

class BayesEstimator final : public MassRegressor {
 public:
  /// params must be valid (see BayesParams::validate). Until reset() the posterior is the
  /// default NigPosterior.
  explicit BayesEstimator(const BayesParams& params);

  void reset(const MassPrior& prior) override;
  PairPrediction predict(const RegressionPair& pair) const override;
  bool update(const RegressionPair& pair) override;
  /// Closes the open batch (if any pair is in it) into the posterior.
  bool flush() override;
  RegressorState state() const override;
  std::string_view name() const override { return "bayes"; }

  const NigPosterior& posterior() const { return posterior_; }
  /// The quantile memo this estimator and its copies share (its counters, for tests).
  const StudentTQuantiles& quantiles() const { return *quantiles_; }
  int pending_pairs() const { return pending_count_; }
  /// Restore a saved posterior (persistence); the open batch starts empty. The posterior must be
  /// finite with V symmetric positive definite, a > 0 and b > 0; otherwise returns false and
  /// changes nothing.
  bool restore(const NigPosterior& posterior, long pairs_used);

  /// The sufficient statistics of a set of pairs, taken about `origin` (a value of theta): with
  /// the residuals e_i = y_i - phi_i origin, phi_t_w_phi = sum w_i phi_i^T phi_i,
  /// phi_t_w_y = sum w_i phi_i^T e_i, y_t_w_y = sum w_i e_i^2. Any origin gives the same
  /// posterior; one close to the posterior mean (the estimator uses the mean at which the batch
  /// opened) avoids the cancellation in bn that raw y^T W y suffers on long runs.
  struct Sufficient {
    Eigen::Vector2d origin = Eigen::Vector2d::Zero();
    Eigen::Matrix2d phi_t_w_phi = Eigen::Matrix2d::Zero();
    Eigen::Vector2d phi_t_w_y = Eigen::Vector2d::Zero();
    double y_t_w_y = 0.0;
    int count = 0;
    double effective_count = 0.0;    ///< sum of the pairs' information (the shape's n)
    double reference_noise_n = 0.0;  ///< noise a pair's own noise_std_n is relative to
    void add(const RegressionPair& pair);
  };
  /// One conjugate update of `prior` by the sufficient statistics of a set of pairs.
  /// Exposed so tests can compare k sequential batches with one batch over all the data.
  /// Returns `prior` unchanged if the result would not be finite.
  static NigPosterior conjugate_update(const NigPosterior& prior, const Sufficient& batch);

 private:
  /// Recompute the quantities cached per posterior (t quantile, predictive inflation).
  void refresh();
  void clear_pending();
  /// The open batch into the posterior (dropped if the result would not be finite).
  bool absorb_pending();

  BayesParams params_;
  NigPosterior posterior_;
  Sufficient pending_;
  int pending_count_ = 0;
  long pairs_used_ = 0;
  double z_q_ = 0.0;  ///< standard normal quantile at (1 + credible_level) / 2
  double t_q_ = 0.0;  ///< Student-t (2 a dof) quantile at the same probability
  std::shared_ptr<StudentTQuantiles> quantiles_;  ///< shared by copies
};

}  // namespace vmass

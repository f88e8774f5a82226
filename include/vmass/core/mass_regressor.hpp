// MassRegressor: the recursive estimator of theta = [M, mu] from RegressionPairs (paper eq. 13).
//
// Two implementations: RlsEstimator (eqs. 14-16 with a noise term, optional forgetting) and
// BayesEstimator (prior-recursive normal-inverse-gamma, eq. 17). The Supervisor talks to either
// through this interface: it asks for the prediction of a pair before deciding to accept it
// (innovation gate), then hands accepted pairs to update().
//
// Not thread-safe; pure computation, no allocation after construction.
#pragma once

#include <string_view>

#include "vmass/core/mass_prior.hpp"
#include "vmass/core/regression_pair.hpp"

namespace vmass {

/// The regressor's current belief about theta, as published.
struct RegressorState {
  double mass_kg = 0.0;
  double mu_n = 0.0;
  double mass_std_kg = 0.0;  ///< standard deviation of M
  double mu_std_n = 0.0;     ///< standard deviation of mu
  double ci_low_kg = 0.0;    ///< 95% interval on M (RLS: Gaussian; Bayes: Student-t credible)
  double ci_high_kg = 0.0;
  double noise_std_n = 0.0;  ///< current estimate (or configured value) of sigma
  long pairs_used = 0;       ///< pairs that have entered the published estimate
};

/// Predictive distribution of a pair's y before it is used: mean and variance (N^2).
struct PairPrediction {
  double y_n = 0.0;
  double variance_n2 = 0.0;
};

class MassRegressor {
 public:
  virtual ~MassRegressor() = default;

  /// Forget everything and start from the prior.
  virtual void reset(const MassPrior& prior) = 0;

  /// Predictive mean and variance of pair.y_n under the current belief, including the noise.
  virtual PairPrediction predict(const RegressionPair& pair) const = 0;

  /// Use an accepted pair. Returns true when the published state changed (RLS: always; Bayes:
  /// when a batch completed).
  virtual bool update(const RegressionPair& pair) = 0;

  /// Take every accepted pair that is not in the published state yet into it (Bayes: the open
  /// batch, however short; RLS: nothing is ever pending). Called at the end of a log and before
  /// the daemon saves its final state, so that no accepted pair is lost. Returns true when the
  /// published state changed.
  virtual bool flush() = 0;

  virtual RegressorState state() const = 0;

  /// "rls" or "bayes".
  virtual std::string_view name() const = 0;
};

}  // namespace vmass

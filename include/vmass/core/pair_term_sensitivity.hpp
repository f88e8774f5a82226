// PairTermSensitivity: how much of the mass estimate rests on one modelled term of the pairs.
//
// A longitudinal pair is y = dF - m_rot dv' (LongitudinalExtractor), and its dF may hold an
// unlocked converter's multiplication. If such a term t_i (the rotating masses' m_rot dv', the
// converter's T (TR - 1) i eta / r differenced) is off by a fraction d in every pair, the
// weighted least-squares mass moves by d S with
//     S = sum w_i da_i t_i / sum w_i da_i^2     (kg)
// over the pairs it was fitted on. That error is the same in every pair, so no amount of
// driving averages it away: it belongs in the interval's model error, as the torque signal's
// scale does. The rotating masses' S is small on a car in top gear (a few % of the mass) and
// large on a truck in its low gears, whose engine inertia reflected through the gearbox can be
// half the empty mass; the converter's is 0 until a pair is read through its map.
// S depends on which gears the pairs come from, not on the load, so it spans load changes. It is
// not in the saved state: a restarted daemon rebuilds it from its first pairs (a ratio of sums,
// it is right from the first one), and until then the interval leaves it out.
#pragma once

#include "vmass/core/regression_pair.hpp"

namespace vmass {

class PairTermSensitivity {
 public:
  /// The sensitivity to the pairs' term `term` (e.g. &RegressionPair::rotating_n).
  explicit PairTermSensitivity(double RegressionPair::*term) : term_(term) {}

  /// A pair the estimate is fitted on, weighted as the regression weighs it (its weight over its
  /// own noise variance; any common factor cancels in S). The pipeline hands it the extractor's
  /// pairs: the supervisor's Huber weights and its rare > 20 sigma rejections are left out.
  void add(const RegressionPair& pair) {
    if (pair.block != Block::kLongitudinal) return;
    const double w =
        pair.noise_std_n > 0.0 ? pair.weight / (pair.noise_std_n * pair.noise_std_n) : pair.weight;
    const double da = pair.delta_accel_mps2;
    sum_da_term_ += w * da * (pair.*term_);
    sum_da_da_ += w * da * da;
  }
  /// S in kg (0 before the first pair).
  double sensitivity_kg() const { return sum_da_da_ > 0.0 ? sum_da_term_ / sum_da_da_ : 0.0; }

 private:
  double RegressionPair::*term_;
  double sum_da_term_ = 0.0;
  double sum_da_da_ = 0.0;
};

}  // namespace vmass

// RotatingMassSensitivity: how much of the mass estimate rests on the rotating masses.
//
// A longitudinal pair is y = dF - m_rot dv' (LongitudinalExtractor). If the configured m_rot is
// off by a fraction d, every pair carries -d m_rot dv' more, and the weighted least-squares mass
// moves by -d S with
//     S = sum w_i da_i m_rot dv'_i / sum w_i da_i^2     (kg)
// over the pairs it was fitted on. That error is the same in every pair, so no amount of
// driving averages it away: it belongs in the interval's model error, as the torque signal's
// scale does. S is small on a car in top gear (a few % of the mass) and large on a truck in its
// low gears, whose engine inertia reflected through the gearbox can be half the empty mass.
// S depends on which gears the pairs come from, not on the load, so it spans load changes. It is
// not in the saved state: a restarted daemon rebuilds it from its first pairs (a ratio of sums,
// it is right from the first one), and until then the interval leaves it out.
#pragma once

#include "vmass/core/regression_pair.hpp"

namespace vmass {

class RotatingMassSensitivity {
 public:
  /// A pair the estimate is fitted on, weighted as the regression weighs it (its weight over its
  /// own noise variance; any common factor cancels in S). The pipeline hands it the extractor's
  /// pairs: the supervisor's Huber weights and its rare > 20 sigma rejections are left out.
  void add(const RegressionPair& pair) {
    if (pair.block != Block::kLongitudinal) return;
    const double w =
        pair.noise_std_n > 0.0 ? pair.weight / (pair.noise_std_n * pair.noise_std_n) : pair.weight;
    const double da = pair.delta_accel_mps2;
    sum_da_rot_ += w * da * pair.rotating_n;
    sum_da_da_ += w * da * da;
  }
  /// S in kg (0 before the first pair).
  double sensitivity_kg() const { return sum_da_da_ > 0.0 ? sum_da_rot_ / sum_da_da_ : 0.0; }

 private:
  double sum_da_rot_ = 0.0;
  double sum_da_da_ = 0.0;
};

}  // namespace vmass

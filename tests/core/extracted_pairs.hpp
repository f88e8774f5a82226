// Test helper: the longitudinal pairs an extractor on its defaults takes from a drive, and the
// mass their plain least squares gives (the regressors' priors and gates left out).
#pragma once

#include <vector>

#include "vmass/core/longitudinal_extractor.hpp"

namespace vmass::testing {

/// Every pair taken, those held while the lag was unknown included.
inline std::vector<RegressionPair> longitudinal_pairs(const std::vector<Sample>& samples,
                                                      const VehicleParams& v) {
  LongitudinalExtractor ex(v, LongitudinalParams{}, DifferencingParams{});
  std::vector<RegressionPair> pairs;
  for (const Sample& s : samples) {
    if (const Extraction e = ex.step(s); e.has_pair()) pairs.push_back(e.pair);
    Extraction released;
    while (ex.pop_released(&released)) pairs.push_back(released.pair);
  }
  return pairs;
}

/// sum da y / sum da^2 over the pairs (0 without a pair).
inline double least_squares_mass(const std::vector<RegressionPair>& pairs) {
  double saa = 0.0, say = 0.0;
  for (const RegressionPair& p : pairs) {
    saa += p.delta_accel_mps2 * p.delta_accel_mps2;
    say += p.delta_accel_mps2 * p.y_n;
  }
  return saa > 0.0 ? say / saa : 0.0;
}

}  // namespace vmass::testing

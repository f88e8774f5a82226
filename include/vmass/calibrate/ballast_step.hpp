// BallastStep: one load step of a static ballast test (the vehicle standing level, a known mass
// added, the rear-right deflection sensor averaged once the body has settled), how samples are
// grouped into steps, and the checks that reject data no stiffness can be fitted to.
//
//   step mean   z_k = (1/n_k) sum_i z_ki           over the samples with added mass m_k
//   step spread s_k = sqrt(sum_i (z_ki - z_k)^2 / (n_k - 1))   (0 for a single sample)
//
// check_steps() says, naming the offending values, when there are fewer than three distinct
// loads, a value is NaN or infinite, two steps share a mass, or the deflection does not increase
// strictly with the load.
//
// Plain values and pure functions; thread-safe.
#pragma once

#include <limits>
#include <string>
#include <vector>

namespace vmass::calibrate {

/// One measurement: the ballast added and the deflection sensor's reading.
struct BallastSample {
  double added_mass_kg = 0.0;
  double deflection_m = 0.0;
};

struct BallastStep {
  double added_mass_kg = 0.0;
  double deflection_m = 0.0;      ///< mean over the step's samples
  double deflection_std_m = 0.0;  ///< spread of the samples (0 for one sample)
  int sample_count = 0;
  /// Time span the step was averaged over (from a time series); NaN when unknown.
  double start_s = std::numeric_limits<double>::quiet_NaN();
  double end_s = std::numeric_limits<double>::quiet_NaN();
};

/// Groups samples by equal added mass (any number per step, in any order) into steps sorted by
/// mass. Non-finite values are kept, so that check_steps() reports them.
std::vector<BallastStep> group_samples(const std::vector<BallastSample>& samples);

/// "" when the steps can be fitted; else what is wrong with them.
std::string check_steps(const std::vector<BallastStep>& steps);

}  // namespace vmass::calibrate

// Synthetic ballast tests with known answers for the calibration tests: deflections from a true
// suspension curve, inverted by bisection on the core's own SuspensionParams::wheel_force_n (an
// answer independent of the fit's closed-form inverse).
#pragma once

#include <cmath>
#include <random>
#include <vector>

#include "vmass/calibrate/ballast_step.hpp"
#include "vmass/calibrate/load_geometry.hpp"
#include "vmass/core/vehicle_params.hpp"

namespace vmass::calibrate::testing {

inline LoadGeometry paper_geometry() {
  LoadGeometry g;
  g.wheelbase_m = 2.70;
  g.cg_to_front_axle_m = 1.20;
  g.gravity_mps2 = 9.80665;
  return g;
}

/// 30 kN/m (the paper's c_Brr), zero reading 12 mm, bump stop 30 mm above it, 2e6 N/m^2.
inline SuspensionParams true_progressive() {
  SuspensionParams s;
  s.stiffness_n_per_m = 30000.0;
  s.empty_deflection_m = 0.012;
  s.progressive_knee_m = 0.042;
  s.progressive_rate_n_per_m2 = 2.0e6;
  return s;
}

inline SuspensionParams true_linear() {
  SuspensionParams s;
  s.stiffness_n_per_m = 30000.0;
  s.empty_deflection_m = 0.012;
  return s;
}

/// z with wheel_force_n(z) = force (bisection to 1e-13 m).
inline double deflection_for_force(const SuspensionParams& s, double force_n) {
  double lo = s.empty_deflection_m - 1.0, hi = s.empty_deflection_m + 1.0;
  for (int i = 0; i < 200 && hi - lo > 1e-13; ++i) {
    const double mid = 0.5 * (lo + hi);
    (s.wheel_force_n(mid) < force_n ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

/// Steps 0, 100, ..., (count-1)*100 kg; per-step Gaussian noise of noise_m (seeded).
inline std::vector<BallastStep> make_steps(const SuspensionParams& s, const LoadGeometry& g,
                                           int count, double noise_m, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> noise(0.0, 1.0);
  std::vector<BallastStep> steps;
  for (int k = 0; k < count; ++k) {
    BallastStep st;
    st.added_mass_kg = 100.0 * k;
    st.deflection_m =
        deflection_for_force(s, g.wheel_force_n(st.added_mass_kg)) + noise_m * noise(rng);
    st.sample_count = 1;
    steps.push_back(st);
  }
  return steps;
}

}  // namespace vmass::calibrate::testing

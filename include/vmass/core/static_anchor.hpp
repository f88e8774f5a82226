// StaticAnchor: a standstill reading of the load (the deflection sensor, eq. 3) as evidence of
// the lumped scale (LearntScale), as a known mass is, but read by the car itself.
//
// The reading is independent of the torque, the radius and the accelerometer, so the drive's
// pairs on that load against it measure kappa: log kappa = log(M_pairs / M_static). The pairs
// must speak alone: the belief the pipeline publishes starts from the reading, so the anchor
// keeps a regression of its own, from a vague prior (anchor_prior_std_fraction), fed the pairs
// the belief takes. The reading's uncertainty has two parts:
//   - the payload's position, which is unknown (StaticInitializer's spread of 1/q, large for a
//     heavy load, small for the driver alone), and the window's noise: this drive's own;
//   - the kerb mass (fuel, options; StaticInitializer::base_std_kg), which every reading of the
//     car shares: LearntScale never lets it average away.
// A load whose position is unknown thus counts little, an empty car much: a static reading
// anchors where the load's position is known.
//
// Pure; not thread-safe (one owner). Allocates only in the constructor.
#pragma once

#include "vmass/core/bayes_estimator.hpp"
#include "vmass/core/known_mass.hpp"
#include "vmass/core/mass_prior.hpp"
#include "vmass/core/regression_pair.hpp"

namespace vmass {

/// A drive's evidence from its static anchor.
struct AnchorObservation {
  double log_scale = 0.0;
  double variance = 0.0;    ///< the drive's own
  double common_std = 0.0;  ///< relative std every reading of the car shares
};

class StaticAnchor {
 public:
  explicit StaticAnchor(const BayesParams& params) : regression_(params) {}

  /// The belief restarted from a standstill reading `reading` (mass and std), of which
  /// common_std_kg is shared by every reading of the car; the pairs are divided by scale_used.
  /// `vague` is the prior its own regression starts from (at the reading's mass).
  void begin(const MassPrior& reading, double common_std_kg, double scale_used,
             const MassPrior& vague);
  /// A pair the belief took (in the belief's units).
  void add(const RegressionPair& pair);
  /// Active with this evidence held, as a saved state gives it back: no pair adds to it.
  void hold(const AnchorObservation& seen);
  bool active() const { return active_; }
  void end() { active_ = false; }

  /// The evidence of the pairs so far; false when inactive, or when they are too few or too
  /// wide (scale_observation's gates).
  bool observation(const LearningParams& params, AnchorObservation* out) const;

 private:
  bool active_ = false;
  bool held_ = false;
  AnchorObservation held_evidence_;
  KnownMass reading_;  ///< its std the drive's own part
  double common_std_kg_ = 0.0;
  BayesEstimator regression_;
};

}  // namespace vmass

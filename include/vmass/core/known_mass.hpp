// KnownMass: a mass the user declared for the current load (a weighbridge ticket, "empty,
// driver only" at delivery), and what the drive on that load says about the lumped scale
// (LearntScale). While it holds, the pipeline publishes it; its regression restarts from it
// with a vague prior, so that the drive's pairs, not the declaration, make the evidence. It
// holds until the load may have changed (a load change seen, a power cycle) or another is
// declared; then the evidence is taken.
//
// Pure; plain values.
#pragma once

#include "vmass/core/learnt_scale.hpp"
#include "vmass/core/mass_regressor.hpp"

namespace vmass {

struct KnownMass {
  bool active = false;
  double mass_kg = 0.0;
  double std_kg = 0.0;      ///< the declaration's own std, > 0
  double scale_used = 1.0;  ///< the learnt scale the drive's pairs were divided by
};

/// One drive's evidence about log kappa.
struct ScaleObservation {
  double log_scale = 0.0;
  double variance = 0.0;
};

/// The evidence of the regression `drive` (on the known load since the declaration); false when
/// it has too few pairs or too wide an interval to say anything (LearningParams).
/// Its variance holds the regression's, the declaration's and the part of the model error that
/// differs from drive to drive (LearningParams::drive_error_std_fraction): kappa holds the rest.
bool scale_observation(const KnownMass& known, const RegressorState& drive,
                       const LearningParams& params, ScaleObservation* out);

}  // namespace vmass

#include "vmass/core/known_mass.hpp"

#include <cmath>

namespace vmass {

bool scale_observation(const KnownMass& known, const RegressorState& drive,
                       const LearningParams& params, ScaleObservation* out) {
  if (!known.active || drive.pairs_used < params.min_evidence_pairs) return false;
  if (!(drive.mass_kg > 0.0) || !(known.mass_kg > 0.0) || !(known.scale_used > 0.0)) return false;
  const double drive_std = drive.mass_std_kg / drive.mass_kg;
  if (!(drive_std < params.max_evidence_std_fraction)) return false;
  const double known_std = known.std_kg / known.mass_kg;
  // The pairs were divided by scale_used: the drive read M * kappa / scale_used.
  out->log_scale = std::log(known.scale_used) + std::log(drive.mass_kg / known.mass_kg);
  out->variance = drive_std * drive_std + known_std * known_std +
                  params.drive_error_std_fraction * params.drive_error_std_fraction;
  return std::isfinite(out->log_scale) && std::isfinite(out->variance);
}

}  // namespace vmass

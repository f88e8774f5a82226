#include "vmass/core/static_anchor.hpp"

#include <algorithm>
#include <cmath>

namespace vmass {

void StaticAnchor::begin(const MassPrior& reading, double common_std_kg, double scale_used,
                         const MassPrior& vague) {
  const double common = std::min(common_std_kg, reading.mass_std_kg);
  const double own_var = reading.mass_std_kg * reading.mass_std_kg - common * common;
  // A reading whose std is all the kerb's still has its window's noise: never exactly zero.
  const double own_std = std::max(std::sqrt(own_var), 1e-3 * reading.mass_kg);
  reading_ = KnownMass{true, reading.mass_kg, own_std, scale_used};
  common_std_kg_ = common;
  MassPrior start = vague;
  start.mass_kg = reading.mass_kg;
  regression_.reset(start);
  active_ = true;
  held_ = false;
}

void StaticAnchor::hold(const AnchorObservation& seen) {
  active_ = true;
  held_ = true;
  held_evidence_ = seen;
}

void StaticAnchor::add(const RegressionPair& pair) {
  if (!active_ || held_ || pair.block != Block::kLongitudinal) return;
  regression_.update(pair);
}

bool StaticAnchor::observation(const LearningParams& params, AnchorObservation* out) const {
  if (!active_) return false;
  if (held_) {
    *out = held_evidence_;
    return true;
  }
  BayesEstimator closed = regression_;
  closed.flush();
  ScaleObservation seen;
  if (!scale_observation(reading_, closed.state(), params, &seen)) return false;
  out->log_scale = seen.log_scale;
  out->variance = seen.variance;
  out->common_std = common_std_kg_ / reading_.mass_kg;
  return true;
}

}  // namespace vmass

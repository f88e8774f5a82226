#include "vmass/core/speed_signal_scale.hpp"

#include <cmath>

namespace vmass {

void SpeedSignalScale::observe(double engine_radps, double through_gear_radps, double speed_mps) {
  if (!(std::abs(speed_mps) >= min_speed_mps_) || !(through_gear_radps > 0.0)) return;
  const double q = engine_radps / through_gear_radps;
  if (!(q >= 1.0 - params_.max_overread && q <= 1.0 + params_.max_underread)) return;
  scale_ += q > scale_ ? params_.step_per_tick : (q < scale_ ? -params_.step_per_tick : 0.0);
}

}  // namespace vmass

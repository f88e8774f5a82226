// BaselineEstimate: what a baseline publishes after a tick. Plain value type.
#pragma once

namespace vmass::baselines {

struct BaselineEstimate {
  bool has_mass = false;  ///< false until the method has an estimate of its own
  double mass_kg = 0.0;
  bool has_interval = false;  ///< 95 % interval when the method gives one
  double ci_low_kg = 0.0, ci_high_kg = 0.0;
  long updates = 0;  ///< pairs/samples that updated the estimate
};

}  // namespace vmass::baselines

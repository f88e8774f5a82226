#include "vmass/scoring/within_tracker.hpp"

namespace vmass::scoring {

void WithinTracker::add(TimeUs t, double error_magnitude) {
  for (std::size_t i = 0; i < kToleranceCount; ++i) {
    if (!(error_magnitude <= tolerances_[i])) last_outside_us_[i] = t;
  }
}

}  // namespace vmass::scoring

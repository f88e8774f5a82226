// Whole ticks in a differencing interval: round(dt * tick rate), at least 1. Pure; thread-safe.
#pragma once

#include <cmath>

namespace vmass::baselines {

inline int differencing_steps(double dt_s, double tick_rate_hz) {
  const double steps = std::round(dt_s * tick_rate_hz);
  return std::isfinite(steps) && steps >= 1.0 ? static_cast<int>(steps) : 1;
}

}  // namespace vmass::baselines

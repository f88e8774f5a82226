#include "vmass/baselines/high_pass_filter.hpp"
#include "vmass/core/constants.hpp"

#include <cmath>

namespace vmass::baselines {

HighPassFilter::HighPassFilter(double cutoff_hz, double sample_rate_hz) {
  if (!(cutoff_hz > 0.0) || !(cutoff_hz < 0.5 * sample_rate_hz)) return;
  enabled_ = true;
  // Bilinear transform of the pre-warped analogue prototype, K = tan(pi fc / fs).
  const double k = std::tan(kPi * cutoff_hz / sample_rate_hz);
  const double k2 = k * k;
  const double norm = 1.0 / (1.0 + std::sqrt(2.0) * k + k2);
  b0_ = norm;
  b1_ = -2.0 * norm;
  b2_ = norm;
  a1_ = 2.0 * (k2 - 1.0) * norm;
  a2_ = (1.0 - std::sqrt(2.0) * k + k2) * norm;
}

double HighPassFilter::step(double x) {
  if (!enabled_) return 0.0;
  if (!primed_) {
    x1_ = x2_ = x;  // steady state for a constant input x: zero output
    y1_ = y2_ = 0.0;
    primed_ = true;
    return 0.0;
  }
  const double y = b0_ * x + b1_ * x1_ + b2_ * x2_ - a1_ * y1_ - a2_ * y2_;
  x2_ = x1_;
  x1_ = x;
  y2_ = y1_;
  y1_ = y;
  return y;
}

}  // namespace vmass::baselines

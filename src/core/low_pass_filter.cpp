#include "vmass/core/low_pass_filter.hpp"
#include "vmass/core/constants.hpp"

#include <cmath>

namespace vmass {

LowPassFilter::LowPassFilter(double cutoff_hz, double sample_rate_hz) {
  if (!(cutoff_hz > 0.0) || !(cutoff_hz < 0.5 * sample_rate_hz)) return;
  enabled_ = true;
  // Pre-warped analogue cutoff, then the bilinear transform with K = tan(pi fc / fs).
  const double k = std::tan(kPi * cutoff_hz / sample_rate_hz);
  const double k2 = k * k;
  const double norm = 1.0 / (1.0 + std::sqrt(2.0) * k + k2);
  b0_ = k2 * norm;
  b1_ = 2.0 * b0_;
  b2_ = b0_;
  a1_ = 2.0 * (k2 - 1.0) * norm;
  a2_ = (1.0 - std::sqrt(2.0) * k + k2) * norm;
}

double LowPassFilter::step(double x) {
  if (!enabled_) return x;
  if (!primed_) {
    x1_ = x2_ = y1_ = y2_ = x;  // start in steady state: no transient from zero
    primed_ = true;
    return x;
  }
  const double y = b0_ * x + b1_ * x1_ + b2_ * x2_ - a1_ * y1_ - a2_ * y2_;
  x2_ = x1_;
  x1_ = x;
  y2_ = y1_;
  y1_ = y;
  return y;
}

}  // namespace vmass

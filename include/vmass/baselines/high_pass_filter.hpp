// HighPassFilter: a second-order Butterworth high-pass (bilinear transform, pre-warped), the
// complement of vmass::LowPassFilter for methods that remove the slowly varying resistive forces
// from both sides of the regression (Fathy et al. 2008). Linear and time-invariant, so a relation
// F = M a + R(t) holds between the filtered signals with R filtered likewise; a constant R is
// removed exactly.
//
//   H(s) = s^2 / (s^2 + sqrt(2) wc s + wc^2)
//
// The first sample after reset() starts the filter in steady state for that input (output 0),
// so a restart after a hole makes no step transient. Not thread-safe; no allocation.
#pragma once

#include "vmass/core/second_order_section.hpp"

namespace vmass::baselines {

class HighPassFilter {
 public:
  /// Requires 0 < cutoff_hz < sample_rate_hz / 2; otherwise the filter outputs 0.
  HighPassFilter(double cutoff_hz, double sample_rate_hz);

  double step(double x);
  void reset() { primed_ = false; }

 private:
  bool enabled_ = false;
  bool primed_ = false;
  SecondOrderSection section_;
};

}  // namespace vmass::baselines

// LowPassFilter: a second-order Butterworth low-pass (bilinear transform, pre-warped), applied
// identically to every signal that enters a difference. Because the filter is linear and
// time-invariant, M da = dF still holds between the filtered signals, while sensor noise above
// the cutoff is removed from both sides of the regression. A cutoff of 0 makes it a pass-through.
//
//   H(s) = wc^2 / (s^2 + sqrt(2) wc s + wc^2)
//
// Not thread-safe; no allocation.
#pragma once

#include "vmass/core/second_order_section.hpp"

namespace vmass {

class LowPassFilter {
 public:
  LowPassFilter() = default;
  /// cutoff_hz = 0 disables filtering; requires cutoff_hz < sample_rate_hz / 2.
  LowPassFilter(double cutoff_hz, double sample_rate_hz);

  /// Filter one sample. The first sample after reset() initialises the state to steady state.
  double step(double x);
  void reset() { primed_ = false; }
  bool enabled() const { return enabled_; }

 private:
  bool enabled_ = false;
  bool primed_ = false;
  SecondOrderSection section_;
};

}  // namespace vmass

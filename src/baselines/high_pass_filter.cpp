#include "vmass/baselines/high_pass_filter.hpp"

namespace vmass::baselines {

HighPassFilter::HighPassFilter(double cutoff_hz, double sample_rate_hz) {
  if (!(cutoff_hz > 0.0) || !(cutoff_hz < 0.5 * sample_rate_hz)) return;
  enabled_ = true;
  section_ = SecondOrderSection::high_pass(cutoff_hz, kButterworthDamping, sample_rate_hz);
}

double HighPassFilter::step(double x) {
  if (!enabled_) return 0.0;
  if (!primed_) {
    section_.settle(x, 0.0);  // steady state for a constant input x: zero output
    primed_ = true;
    return 0.0;
  }
  return section_.step(x);
}

}  // namespace vmass::baselines

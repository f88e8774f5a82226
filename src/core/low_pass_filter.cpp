#include "vmass/core/low_pass_filter.hpp"

namespace vmass {

LowPassFilter::LowPassFilter(double cutoff_hz, double sample_rate_hz) {
  if (!(cutoff_hz > 0.0) || !(cutoff_hz < 0.5 * sample_rate_hz)) return;
  enabled_ = true;
  section_ = SecondOrderSection::low_pass(cutoff_hz, kButterworthDamping, sample_rate_hz);
}

double LowPassFilter::step(double x) {
  if (!enabled_) return x;
  if (!primed_) {
    section_.settle(x, 1.0);  // start in steady state: no transient from zero
    primed_ = true;
    return x;
  }
  return section_.step(x);
}

}  // namespace vmass

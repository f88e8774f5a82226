// The low-pass before differencing: unity DC gain, -3 dB at the cutoff, and the property the
// extractors rely on: filtering both sides of M a = F keeps the relation exact.
#include "vmass/core/low_pass_filter.hpp"
#include "vmass/core/constants.hpp"

#include <cmath>

#include <gtest/gtest.h>

namespace vmass {
namespace {

double steady_amplitude(double freq_hz, double cutoff_hz) {
  LowPassFilter f(cutoff_hz, 100.0);
  double peak = 0.0;
  for (int k = 0; k < 4000; ++k) {
    const double y = f.step(std::sin(2.0 * kPi * freq_hz * k / 100.0));
    if (k > 2000) peak = std::max(peak, std::abs(y));
  }
  return peak;
}

TEST(LowPassFilter, UnityAtDcAndMinus3dBAtCutoff) {
  LowPassFilter f(5.0, 100.0);
  double y = 0.0;
  for (int k = 0; k < 500; ++k) y = f.step(k == 0 ? 0.0 : 2.5);
  EXPECT_NEAR(y, 2.5, 1e-9);
  EXPECT_NEAR(steady_amplitude(5.0, 5.0), 1.0 / std::sqrt(2.0), 0.01);
  EXPECT_LT(steady_amplitude(25.0, 5.0), 0.05);
}

TEST(LowPassFilter, LinearSoFilteredRelationStaysExact) {
  LowPassFilter fa(5.0, 100.0), ff(5.0, 100.0);
  const double mass = 1650.0;
  for (int k = 0; k < 1000; ++k) {
    const double a = std::sin(0.05 * k) + 0.3 * std::sin(0.9 * k);
    const double fa_k = fa.step(a);
    const double ff_k = ff.step(mass * a);
    ASSERT_NEAR(ff_k, mass * fa_k, 1e-9 * mass);
  }
}

TEST(LowPassFilter, ZeroCutoffPassesThrough) {
  LowPassFilter f(0.0, 100.0);
  EXPECT_FALSE(f.enabled());
  EXPECT_EQ(f.step(3.25), 3.25);
}

}  // namespace
}  // namespace vmass

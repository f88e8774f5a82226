// The biquad every second-order filter of the project is built on: a low-pass and a high-pass
// at one corner are complementary in power (Butterworth), the resonance of a lightly damped
// section sits at its corner with a gain of 1 / (2 zeta), and settle() starts either kind in
// the steady state of a constant input.
#include "vmass/core/second_order_section.hpp"
#include "vmass/core/constants.hpp"

#include <algorithm>
#include <cmath>

#include <gtest/gtest.h>

namespace vmass {
namespace {

constexpr double kRateHz = 100.0;

double steady_amplitude(SecondOrderSection s, double freq_hz) {
  double peak = 0.0;
  for (int k = 0; k < 6000; ++k) {
    const double y = s.step(std::sin(2.0 * kPi * freq_hz * k / kRateHz));
    if (k > 4000) peak = std::max(peak, std::abs(y));
  }
  return peak;
}

TEST(SecondOrderSection, ButterworthLowAndHighPassAreComplementaryInPower) {
  for (const double f : {0.5, 2.0, 5.0, 12.0}) {
    const double lo =
        steady_amplitude(SecondOrderSection::low_pass(5.0, kButterworthDamping, kRateHz), f);
    const double hi =
        steady_amplitude(SecondOrderSection::high_pass(5.0, kButterworthDamping, kRateHz), f);
    EXPECT_NEAR(lo * lo + hi * hi, 1.0, 0.01) << f << " Hz";
  }
}

TEST(SecondOrderSection, ALightlyDampedSectionResonatesAtItsCorner) {
  const double zeta = 0.15;
  const SecondOrderSection mode = SecondOrderSection::low_pass(2.0, zeta, kRateHz);
  EXPECT_NEAR(steady_amplitude(mode, 2.0), 1.0 / (2.0 * zeta), 0.05);
  // Below resonance: the static gain 1 amplified by about 1 / (1 - (f / f_n)^2).
  EXPECT_NEAR(steady_amplitude(mode, 0.5), 1.0 / (1.0 - 0.25 * 0.25), 0.01);
}

TEST(SecondOrderSection, SettleStartsInTheSteadyStateOfAConstantInput) {
  SecondOrderSection lo = SecondOrderSection::low_pass(1.0, 0.15, kRateHz);
  SecondOrderSection hi = SecondOrderSection::high_pass(1.0, kButterworthDamping, kRateHz);
  lo.settle(3.0, 1.0);
  hi.settle(3.0, 0.0);
  for (int k = 0; k < 200; ++k) {
    ASSERT_NEAR(lo.step(3.0), 3.0, 1e-9);
    ASSERT_NEAR(hi.step(3.0), 0.0, 1e-9);
  }
}

}  // namespace
}  // namespace vmass

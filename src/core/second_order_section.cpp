#include "vmass/core/second_order_section.hpp"

#include <cmath>

#include "vmass/core/constants.hpp"

namespace vmass {

namespace {

// K = tan(pi f / fs) pre-warps the corner; the denominator is shared by both kinds.
SecondOrderSection bilinear(double corner_hz, double zeta, double rate_hz, bool high_pass) {
  const double k = std::tan(kPi * corner_hz / rate_hz);
  const double k2 = k * k;
  const double norm = 1.0 / (1.0 + 2.0 * zeta * k + k2);
  SecondOrderSection s;
  s.b0 = (high_pass ? 1.0 : k2) * norm;
  s.b1 = (high_pass ? -2.0 : 2.0) * s.b0;
  s.b2 = s.b0;
  s.a1 = 2.0 * (k2 - 1.0) * norm;
  s.a2 = (1.0 - 2.0 * zeta * k + k2) * norm;
  return s;
}

}  // namespace

SecondOrderSection SecondOrderSection::low_pass(double corner_hz, double damping_ratio,
                                                double rate_hz) {
  return bilinear(corner_hz, damping_ratio, rate_hz, false);
}

SecondOrderSection SecondOrderSection::high_pass(double corner_hz, double damping_ratio,
                                                 double rate_hz) {
  return bilinear(corner_hz, damping_ratio, rate_hz, true);
}

double SecondOrderSection::step(double x) {
  const double y = b0 * x + b1 * x1 + b2 * x2 - a1 * y1 - a2 * y2;
  x2 = x1;
  x1 = x;
  y2 = y1;
  y1 = y;
  return y;
}

void SecondOrderSection::settle(double x, double static_gain) {
  x1 = x2 = x;
  y1 = y2 = x * static_gain;
}

}  // namespace vmass

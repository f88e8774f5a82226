// SecondOrderSection: one biquad, direct form I, with the bilinear transform (pre-warped at its
// corner) of the analogue second-order low-pass w^2 / (s^2 + 2 zeta w s + w^2) or high-pass
// s^2 / (...). Every second-order filter of the project is one of these: the regression's
// low-pass, the baselines' high-pass, the driveline mode and its identification's band-pass.
//
// Not thread-safe; no allocation.
#pragma once

namespace vmass {

struct SecondOrderSection {
  double b0 = 1.0, b1 = 0.0, b2 = 0.0, a1 = 0.0, a2 = 0.0;
  double x1 = 0.0, x2 = 0.0, y1 = 0.0, y2 = 0.0;

  /// Requires 0 < corner_hz < rate_hz / 2.
  static SecondOrderSection low_pass(double corner_hz, double damping_ratio, double rate_hz);
  static SecondOrderSection high_pass(double corner_hz, double damping_ratio, double rate_hz);

  double step(double x);
  /// The state of a steady input x (the output equal to x times the static gain).
  void settle(double x, double static_gain);
};

/// The damping ratio of a Butterworth pair, 1/sqrt(2).
inline constexpr double kButterworthDamping = 0.7071067811865476;

}  // namespace vmass

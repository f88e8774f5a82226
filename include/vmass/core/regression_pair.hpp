// RegressionPair: one extracted event y = phi * theta + e of the paper's eq. (13).
//
//   y   = Delta(F)            the differenced force, N (longitudinal: traction - brake, corrected
//                             for rotating inertia; lateral: F_yf cos(delta_f) + F_yr)
//   phi = [Delta(a), 1]       the differenced acceleration, m/s^2, and the intercept
//   theta = [M, mu]           mass, kg, and the model imprecision mu, N
//   e ~ N(0, sigma^2 / weight)
//
// The weight lets blocks with different noise levels share one regression (longitudinal and
// lateral pairs are not equally precise); weight 1 is the reference block.
// The information is how many independent observations the pair is worth: pairs taken every
// tick from low-pass filtered signals share their noise with their neighbours, and counting
// each as a full observation would make the interval too narrow. The regressors use
// weight * information as the pair's precision and information as its count (Bayes' shape),
// while the innovation gate uses the pair's own noise (weight only).
#pragma once

#include <cstdint>
#include <string_view>

#include "vmass/core/time.hpp"

namespace vmass {

enum class Block : std::uint8_t { kLongitudinal = 0, kLateral = 1 };
constexpr int kBlockCount = 2;
std::string_view block_name(Block b);

struct RegressionPair {
  TimeUs time_us = 0;
  Block block = Block::kLongitudinal;
  double y_n = 0.0;               ///< differenced force, N
  double delta_accel_mps2 = 0.0;  ///< phi[0], differenced acceleration, m/s^2
  double weight = 1.0;            ///< relative precision, > 0
  double information = 1.0;       ///< independent observations this pair is worth, in (0, 1]
  /// The pair's own noise std, as its extractor measures it, N; 0: the regressor's configured
  /// noise applies. With it, a regressor whose noise is s weighs the pair as weight * (s / it)^2.
  double noise_std_n = 0.0;
  /// Longitudinal: the rotating-mass term m_rot dv' already subtracted from y_n, N (0 for the
  /// lateral block). An error in m_rot biases the mass through it (PairTermSensitivity).
  double rotating_n = 0.0;
  /// Longitudinal: the part of y_n an unlocked converter's multiplication makes, T (TR - 1) i
  /// eta / r differenced, N (0 while locked). An error in the converter's map biases the mass
  /// through it, as rotating_n's does.
  double converter_n = 0.0;
  /// Longitudinal: the gear (or derived-ratio plateau) that term's rotating mass is taken for,
  /// 0 none, and that mass as configured, kg: what a study of the rotating masses per gear reads.
  int gear = 0;
  double rotating_mass_kg = 0.0;
  /// Longitudinal: the wheels' differenced acceleration dv', m/s^2, that the rotating term
  /// multiplies (a learnt correction of the gear's rotating mass is subtracted times it): the
  /// wheel speed's, or the accelerometer's where the speed signal is too coarse.
  double wheel_delta_accel_mps2 = 0.0;
};

/// The pair's weight relative to a regressor whose noise std is reference_noise_n (see
/// RegressionPair::noise_std_n).
inline double relative_weight(const RegressionPair& pair, double reference_noise_n) {
  if (!(pair.noise_std_n > 0.0)) return pair.weight;
  const double ratio = reference_noise_n / pair.noise_std_n;
  return pair.weight * ratio * ratio;
}

}  // namespace vmass

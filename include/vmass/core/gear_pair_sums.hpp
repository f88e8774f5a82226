// GearPairSums: a regression's longitudinal pairs summed per gear, for what the gears tell about
// the rotating masses (LearntGearMasses).
//
// A pair in gear g reads y = M da + delta_g dv' + mu, with delta_g the error of the rotating mass
// the config gives for g and dv' the wheels' differenced acceleration. Per gear it keeps, with
// the pair's precision p = weight * information / noise^2:
//   sum p da^2, sum p da y, sum p da  -> the gear's effective mass over the drive (the evidence)
//   sum p da dv'                      -> how much the mass estimate rests on delta_g
// and over all pairs sum p da^2 and sum p da rotating_n of the pairs outside the learnt gears.
// y is the pair's force before any learnt correction (in the belief's units). Sums add, so the
// pairs of a stretch are the difference of two snapshots.
//
// Pure; plain values.
#pragma once

#include <array>

#include "vmass/core/regression_pair.hpp"

namespace vmass {

/// Gears whose rotating mass is learnt (a truck's 16-speed box at most).
constexpr int kMaxLearntGears = 16;

struct GearPairSums {
  std::array<double, kMaxLearntGears> da_da{};
  std::array<double, kMaxLearntGears> da_y{};
  std::array<double, kMaxLearntGears> da{};
  std::array<double, kMaxLearntGears> da_wheel{};
  std::array<long, kMaxLearntGears> pairs{};
  double all_da_da = 0.0;         ///< over every longitudinal pair
  double unlearnt_da_term = 0.0;  ///< sum p da rotating_n of pairs outside the learnt gears

  /// The learnt gear (0-based) a pair counts for, or -1: no gear, beyond `gears`, or read
  /// through an unlocked converter (whose engine side turns on its own).
  static int slot(const RegressionPair& pair, int gears) {
    if (pair.block != Block::kLongitudinal || pair.gear < 1 || pair.gear > gears ||
        pair.converter_n != 0.0) {
      return -1;
    }
    return pair.gear - 1;
  }

  /// A pair the regression was fitted on; uncorrected_y_n its force before the learnt correction.
  void add(const RegressionPair& pair, double uncorrected_y_n, int gears) {
    if (pair.block != Block::kLongitudinal) return;
    const double p = pair.noise_std_n > 0.0
                         ? pair.weight * pair.information / (pair.noise_std_n * pair.noise_std_n)
                         : pair.weight * pair.information;
    const double a = pair.delta_accel_mps2;
    all_da_da += p * a * a;
    const int g = slot(pair, gears);
    if (g < 0) {
      unlearnt_da_term += p * a * pair.rotating_n;
      return;
    }
    const auto i = static_cast<std::size_t>(g);
    da_da[i] += p * a * a;
    da_y[i] += p * a * uncorrected_y_n;
    da[i] += p * a;
    da_wheel[i] += p * a * pair.wheel_delta_accel_mps2;
    ++pairs[i];
  }

  /// The pairs added since `before` (a snapshot of these sums).
  GearPairSums since(const GearPairSums& before) const {
    GearPairSums d = *this;
    for (std::size_t i = 0; i < d.pairs.size(); ++i) {
      d.da_da[i] -= before.da_da[i];
      d.da_y[i] -= before.da_y[i];
      d.da[i] -= before.da[i];
      d.da_wheel[i] -= before.da_wheel[i];
      d.pairs[i] -= before.pairs[i];
    }
    d.all_da_da -= before.all_da_da;
    d.unlearnt_da_term -= before.unlearnt_da_term;
    return d;
  }
};

}  // namespace vmass

// PairTermSums: what the drive's own pairs tell about the errors of two modelled terms of the
// longitudinal pairs, and what those errors do to the mass.
//
// A longitudinal pair is y = dF - m_rot(g) dv' (LongitudinalExtractor): the configured rotating
// mass of its gear times the wheels' differenced acceleration, rotating_n, is taken off, and
// while an automatic's converter is unlocked dF holds the multiplication its map gives,
// converter_n. If the configured rotating masses are off by one fraction in every gear (the
// engine's and the wheels' inertia of a datasheet, +-30 %) and the map by another, the pairs
// read
//     y = M da + mu + c_rot rotating_n + c_conv converter_n,
// and the two-parameter regression [M, mu] reads M plus c_rot and c_conv times the mass's
// sensitivities to the terms (PairTermSensitivity): 1-2 t of a truck's mass in its low gears.
// Within one gear, rotating_n is m_rot(g) times the wheels' dv', which follows da: c_rot cannot
// be told from M (a fit on dv' would read the two signals' different noise and delay as c_rot).
// Across gears whose rotating masses differ (a truck's 14x from first to top gear, a car's 3x)
// it can: so the fit's column is m_rot(g) da, the pair's configured rotating_mass_kg times its da,
// and c_conv's is converter_n, told from the pairs with and without the converter multiplying.
// Both are parameters, each ~ N(0, prior std^2) (the datasheet's accuracy); the sums give:
//   - the shift of the mass from the two-parameter fit to the four-parameter one
//     (Frisch-Waugh: the regression's mass plus this shift is the mass with both estimated);
//   - the std of the mass that their remaining uncertainty leaves, sqrt(Var4 - Var2): with one
//     gear and no converter, prior std |S| (the datasheet's term of the interval); with gears
//     that tell c_rot, less.
// Each pair weighs weight * information / noise^2, as the regression weighs it; the sums add,
// so a stretch's pairs are the difference of two snapshots.
//
// Pure; plain values; no allocation.
#pragma once

#include <array>
#include <string>

#include <Eigen/Core>

#include "vmass/core/regression_pair.hpp"

namespace vmass {

struct PairTermPriors {
  double rotating_std = 0.0;   ///< of c_rot; 0: the configured masses are taken as exact
  double converter_std = 0.0;  ///< of c_conv; 0: the map is taken as exact
};

struct PairTermFit {
  double mass_shift_kg = 0.0;  ///< add to the two-parameter regression's mass
  double mass_std_kg = 0.0;    ///< the mass's std from the terms' remaining uncertainty
  /// c_rot: the true rotating masses are (1 + c_rot) times the configured ones.
  double rotating_error = 0.0;
  double rotating_error_std = 0.0;
  /// c_conv: the pairs' y misses -c_conv of the map's multiplication, so the true
  /// multiplication (TR - 1) is (1 - c_conv) times the map's.
  double converter_error = 0.0;
  double converter_error_std = 0.0;
  long pairs = 0;                     ///< the pairs fitted
  bool converter_multiplied = false;  ///< some of them held the converter's multiplication
};

/// The sums as plain values, for the state file: the normal matrix row-major, its moment.
struct PairTermSumsState {
  std::array<double, 16> normal{};
  std::array<double, 4> moment{};
  long pairs = 0;
};

class PairTermSums {
 public:
  PairTermSumsState state() const;
  /// Empty when `saved` could be these sums (finite, symmetric, a non-negative diagonal and
  /// pair count), else why not, naming the field.
  static std::string implausible(const PairTermSumsState& saved);
  /// Sums from a plausible state (see implausible()); an implausible one gives empty sums.
  static PairTermSums restored(const PairTermSumsState& saved);

  /// A longitudinal pair the regression is fitted on (others are ignored); reference_noise_n
  /// is the noise of a pair that does not carry its own (RegressionPair::noise_std_n == 0).
  void add(const RegressionPair& pair, double reference_noise_n);
  /// The pairs added since `before` (a snapshot of these sums).
  PairTermSums since(const PairTermSums& before) const;
  long pairs() const { return pairs_; }

  /// The fit. Without a well-posed two-parameter fit (fewer than two pairs, or accelerations
  /// that do not differ) the shift is 0 and the std the datasheet's, prior std |S| per term.
  PairTermFit fit(const PairTermPriors& priors) const;

 private:
  using Matrix4 = Eigen::Matrix<double, 4, 4>;
  using Vector4 = Eigen::Matrix<double, 4, 1>;
  /// sum p phi phi^T, phi = [da, 1, rotating_mass_kg da, converter_n]
  Matrix4 normal_ = Matrix4::Zero();
  Vector4 moment_ = Vector4::Zero();  ///< sum p phi y
  long pairs_ = 0;
};

}  // namespace vmass

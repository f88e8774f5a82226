#include "vmass/core/pair_term_fit.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/Cholesky>

namespace vmass {

namespace {

constexpr int kMass = 0;
constexpr int kRotating = 2;
constexpr int kConverter = 3;

/// The row-major index of (r, c) in PairTermSumsState::normal.
std::size_t at(int r, int c) {
  return static_cast<std::size_t>(r) * 4 + static_cast<std::size_t>(c);
}

/// The datasheet's answer: each term's error moves the mass by its sensitivity, independently.
PairTermFit datasheet_fit(const Eigen::Matrix<double, 4, 4>& normal, long pairs,
                          const PairTermPriors& p) {
  PairTermFit out;
  out.pairs = pairs;
  out.converter_multiplied = normal(kConverter, kConverter) > 0.0;
  out.rotating_error_std = p.rotating_std;
  out.converter_error_std = p.converter_std;
  const double da_da = normal(kMass, kMass);
  if (!(da_da > 0.0)) return out;
  out.mass_std_kg = std::hypot(p.rotating_std * normal(kMass, kRotating) / da_da,
                               p.converter_std * normal(kMass, kConverter) / da_da);
  return out;
}

}  // namespace

void PairTermSums::add(const RegressionPair& pair, double reference_noise_n) {
  if (pair.block != Block::kLongitudinal) return;
  const double noise = pair.noise_std_n > 0.0 ? pair.noise_std_n : reference_noise_n;
  if (!(noise > 0.0)) return;
  const double p = pair.weight * pair.information / (noise * noise);
  // The gear's configured rotating mass times da rather than rotating_n (m_rot dv'): within a
  // gear the column is then exactly proportional to da, and the scale is told from the gears
  // alone, not from how the wheel speed's and the accelerometer's noise and delay differ.
  const double da = pair.delta_accel_mps2;
  const Vector4 phi(da, 1.0, pair.rotating_mass_kg * da, pair.converter_n);
  if (!phi.allFinite() || !std::isfinite(pair.y_n) || !(p > 0.0) || !std::isfinite(p)) return;
  normal_ += p * phi * phi.transpose();
  moment_ += p * pair.y_n * phi;
  ++pairs_;
}

PairTermSumsState PairTermSums::state() const {
  PairTermSumsState out;
  for (int r = 0; r < 4; ++r) {
    for (int c = 0; c < 4; ++c) out.normal[at(r, c)] = normal_(r, c);
    out.moment[static_cast<std::size_t>(r)] = moment_(r);
  }
  out.pairs = pairs_;
  return out;
}

std::string PairTermSums::implausible(const PairTermSumsState& saved) {
  if (saved.pairs < 0) return "pair_term_pairs: negative";
  for (double x : saved.moment) {
    if (!std::isfinite(x)) return "pair_term_moment: not finite";
  }
  for (int r = 0; r < 4; ++r) {
    for (int c = 0; c < 4; ++c) {
      const double x = saved.normal[at(r, c)];
      const double mirror = saved.normal[at(c, r)];
      if (!std::isfinite(x)) return "pair_term_normal: not finite";
      if (std::abs(x - mirror) > 1e-9 * (std::abs(x) + std::abs(mirror))) {
        return "pair_term_normal: not symmetric";
      }
    }
    if (saved.normal[at(r, r)] < 0.0) {
      return "pair_term_normal: a negative diagonal";
    }
  }
  return "";
}

PairTermSums PairTermSums::restored(const PairTermSumsState& saved) {
  PairTermSums out;
  if (!implausible(saved).empty()) return out;
  for (int r = 0; r < 4; ++r) {
    for (int c = 0; c < 4; ++c) out.normal_(r, c) = saved.normal[at(r, c)];
    out.moment_(r) = saved.moment[static_cast<std::size_t>(r)];
  }
  out.pairs_ = saved.pairs;
  return out;
}

PairTermSums PairTermSums::since(const PairTermSums& before) const {
  PairTermSums d = *this;
  d.normal_ -= before.normal_;
  d.moment_ -= before.moment_;
  d.pairs_ -= before.pairs_;
  return d;
}

PairTermFit PairTermSums::fit(const PairTermPriors& priors) const {
  const PairTermFit datasheet = datasheet_fit(normal_, pairs_, priors);
  const Eigen::Matrix2d normal2 = normal_.topLeftCorner<2, 2>();
  // Accelerations that all equal one value cannot tell M from mu.
  const double determinant = normal2(0, 0) * normal2(1, 1) - normal2(0, 1) * normal2(0, 1);
  if (pairs_ < 2 || !(determinant > 1e-12 * normal2(0, 0) * normal2(1, 1))) return datasheet;
  // A term with no prior std is exact: its parameter is pinned to 0 (an identity row).
  Matrix4 normal4 = normal_;
  Vector4 moment4 = moment_;
  const double stds[2] = {priors.rotating_std, priors.converter_std};
  for (int k = 0; k < 2; ++k) {
    const int i = kRotating + k;
    if (stds[k] > 0.0) {
      normal4(i, i) += 1.0 / (stds[k] * stds[k]);
      continue;
    }
    normal4.row(i).setZero();
    normal4.col(i).setZero();
    normal4(i, i) = 1.0;
    moment4(i) = 0.0;
  }
  const Eigen::LDLT<Eigen::Matrix2d> two(normal2);
  const Eigen::LDLT<Matrix4> four(normal4);
  if (two.info() != Eigen::Success || four.info() != Eigen::Success) return datasheet;
  const Eigen::Vector2d theta2 = two.solve(moment_.head<2>());
  const Vector4 theta4 = four.solve(moment4);
  const double var2 = two.solve(Eigen::Vector2d::UnitX())(kMass);
  const Matrix4 covariance4 = four.solve(Matrix4::Identity());
  if (!theta2.allFinite() || !theta4.allFinite() || !std::isfinite(var2) ||
      !covariance4.allFinite()) {
    return datasheet;
  }
  PairTermFit out = datasheet;  // its pair count and converter flag; the rest is fitted below
  out.mass_shift_kg = theta4(kMass) - theta2(kMass);
  out.mass_std_kg = std::sqrt(std::max(0.0, covariance4(kMass, kMass) - var2));
  out.rotating_error = theta4(kRotating);
  out.rotating_error_std =
      priors.rotating_std > 0.0 ? std::sqrt(std::max(0.0, covariance4(kRotating, kRotating))) : 0.0;
  out.converter_error = theta4(kConverter);
  out.converter_error_std = priors.converter_std > 0.0
                                ? std::sqrt(std::max(0.0, covariance4(kConverter, kConverter)))
                                : 0.0;
  return out;
}

}  // namespace vmass

#include "vmass/core/learnt_gear_masses.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

namespace vmass {
namespace {

constexpr int kMax = kMaxLearntGears;
// Sized at most kMax: no allocation.
using Vector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMax, 1>;
using Matrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kMax, kMax>;

constexpr double kUniformStdPerBound = 0.5773502691896258;  // std = bound / sqrt(3)
/// |relative level| the scale may hold for the gears: as the learnt scale's own bound.
constexpr double kMaxReferenceLevel = 0.25;

/// The index of covariance (i, j) in GearMassesState::covariance_kg2.
std::size_t cell(int i, int j) {
  return static_cast<std::size_t>(i) * static_cast<std::size_t>(kMax) + static_cast<std::size_t>(j);
}

Matrix covariance(const GearMassesState& s) {
  Matrix c(s.gears, s.gears);
  for (int i = 0; i < s.gears; ++i) {
    for (int j = 0; j < s.gears; ++j) c(i, j) = s.covariance_kg2[cell(i, j)];
  }
  return c;
}

Vector mean(const GearMassesState& s) {
  Vector m(s.gears);
  for (int i = 0; i < s.gears; ++i) m(i) = s.correction_kg[std::size_t(i)];
  return m;
}

void store(const Vector& m, const Matrix& c, GearMassesState* s) {
  for (int i = 0; i < s->gears; ++i) {
    s->correction_kg[std::size_t(i)] = m(i);
    for (int j = 0; j < s->gears; ++j) {
      s->covariance_kg2[cell(i, j)] = 0.5 * (c(i, j) + c(j, i));
    }
  }
}

// The scale's mean is its evidence weighed by precision, the datasheet's mean (0 in log) among
// them: of a known-mass drive's relative level sum_g s_g (delta_g - c_g) / M it holds the share
// its evidence weighs. The belief's mean stands for delta.
double reference_level(const GearMassesState& s) {
  if (!(s.reference_precision > 0.0)) return 0.0;
  double sum = -s.reference_applied;
  for (int i = 0; i < s.gears; ++i) {
    sum += s.reference_share_per_kg[std::size_t(i)] * s.correction_kg[std::size_t(i)];
  }
  return sum / s.reference_precision;
}

}  // namespace

LearntGearMasses::LearntGearMasses(const std::vector<double>& rotating_mass_by_gear_kg,
                                   double accuracy_fraction, double floor_fraction,
                                   long min_gear_pairs)
    : std_fraction_(kUniformStdPerBound * accuracy_fraction),
      floor_fraction_(floor_fraction),
      min_gear_pairs_(std::max(1L, min_gear_pairs)) {
  const int gears = static_cast<int>(std::min<std::size_t>(rotating_mass_by_gear_kg.size(), kMax));
  bool usable = gears >= 2 && std_fraction_ > 0.0;
  for (int i = 0; i < gears; ++i) {
    const double kg = rotating_mass_by_gear_kg[std::size_t(i)];
    usable = usable && kg > 0.0 && std::isfinite(kg);
    config_kg_[std::size_t(i)] = kg;
  }
  state_.gears = usable ? gears : 0;
  reset();
}

// The datasheet's error in equal parts common to every gear (one inertia reflected through
// each) and each gear's own (the measured per-gear residues of the driveline).
double LearntGearMasses::prior_variance_kg2(int i, int j) const {
  // (m_i m_j) first: the product is the same either way round, so the matrix is symmetric.
  const double common =
      std_fraction_ * std_fraction_ * (config_kg_[std::size_t(i)] * config_kg_[std::size_t(j)]);
  return i == j ? 2.0 * common : common;
}

void LearntGearMasses::reset() {
  const int gears = state_.gears;
  state_ = GearMassesState{};
  state_.gears = gears;
  for (int i = 0; i < gears; ++i) {
    for (int j = 0; j < gears; ++j) {
      state_.covariance_kg2[cell(i, j)] = prior_variance_kg2(i, j);
    }
  }
  refresh_scale_factor();
}

double LearntGearMasses::correction_kg(int gear) const {
  if (gear < 1 || gear > state_.gears) return 0.0;
  return state_.correction_kg[std::size_t(gear - 1)];
}

void LearntGearMasses::refresh_scale_factor() {
  ++revision_;
  // The evidence read (M + level M) / M: divided out exactly, not in its logarithm.
  scale_factor_ = 1.0 / (1.0 + reference_level(state_));
}

void LearntGearMasses::add_reference(const GearPairSums& sums, double mass_kg,
                                     double evidence_variance, double scale_prior_variance,
                                     const LearntGearMasses& applied) {
  if (state_.gears == 0 || applied.gears() != state_.gears || !(sums.all_da_da > 0.0) ||
      !(mass_kg > 0.0) || !(evidence_variance > 0.0) || !std::isfinite(evidence_variance) ||
      !(scale_prior_variance > 0.0)) {
    return;
  }
  GearMassesState next = state_;
  if (next.reference_precision == 0.0) next.reference_precision = 1.0 / scale_prior_variance;
  next.reference_precision += 1.0 / evidence_variance;
  const double weight = 1.0 / (evidence_variance * mass_kg);
  for (int i = 0; i < next.gears; ++i) {
    const double share = sums.da_wheel[std::size_t(i)] / sums.all_da_da;
    if (share > 0.0 && std::isfinite(share)) {
      next.reference_share_per_kg[std::size_t(i)] += share * weight;
      next.reference_applied += share * weight * applied.correction_kg(i + 1);
    }
  }
  if (!implausible(next).empty()) return;
  state_ = next;
  refresh_scale_factor();
}

double LearntGearMasses::correction_std_kg(int gear) const {
  if (gear < 1 || gear > state_.gears) return 0.0;
  return std::sqrt(state_.covariance_kg2[cell(gear - 1, gear - 1)]);
}

double LearntGearMasses::mass_variance_kg2(const GearPairSums& sums, double mass_kg) const {
  if (state_.gears == 0 || !(sums.all_da_da > 0.0)) return 0.0;
  // dM / d delta_g = sum_g p da dv' / sum p da^2 (LS mass with delta_g dv' in every y of g),
  // less what the scale factor takes off the whole mass for it.
  Vector s = Vector::Zero(state_.gears);
  for (int i = 0; i < state_.gears; ++i) {
    s(i) = sums.da_wheel[std::size_t(i)] / sums.all_da_da;
    if (state_.reference_precision > 0.0 && mass_kg > 0.0) {
      s(i) -= mass_kg * state_.reference_share_per_kg[std::size_t(i)] / state_.reference_precision;
    }
  }
  return s.dot(covariance(state_) * s);
}

LearntGearMasses LearntGearMasses::with_evidence(const GearPairSums& sums, double mass_kg,
                                                 double mu_n) const {
  LearntGearMasses out = *this;
  out.add_evidence(sums, mass_kg, mu_n);
  return out;
}

bool LearntGearMasses::add_evidence(const GearPairSums& sums, double mass_kg, double mu_n) {
  const int n = state_.gears;
  if (n == 0 || !(mass_kg > 0.0) || !std::isfinite(mass_kg) || !std::isfinite(mu_n)) {
    return false;
  }
  // Each gear's effective mass over the drive (M + delta_g), and its variance with the floor.
  const double floor_kg = floor_fraction_ * mass_kg;
  Vector precision = Vector::Zero(n);
  Vector reading = Vector::Zero(n);
  int used = 0;
  for (int i = 0; i < n; ++i) {
    const auto k = std::size_t(i);
    if (sums.pairs[k] < min_gear_pairs_ || !(sums.da_da[k] > 0.0)) continue;
    reading(i) = (sums.da_y[k] - mu_n * sums.da[k]) / sums.da_da[k];
    precision(i) = 1.0 / (1.0 / sums.da_da[k] + floor_kg * floor_kg);
    if (!std::isfinite(reading(i))) return false;
    ++used;
  }
  if (used < 2) return false;
  // The drive's mass profiled out: u - M 1 - delta ~ N(0, W^-1) with M unknown leaves the
  // information A = W - w w' / sum w about delta, and A u.
  const Matrix w = precision.asDiagonal();
  const Matrix a = w - precision * precision.transpose() / precision.sum();
  const Vector au = a * reading;
  // The normal update in information form.
  const Matrix prior_cov = covariance(state_);
  const Eigen::LDLT<Matrix> prior(prior_cov);
  if (prior.info() != Eigen::Success) return false;
  const Matrix info = prior.solve(Matrix::Identity(n, n)) + a;
  const Eigen::LDLT<Matrix> posterior(info);
  if (posterior.info() != Eigen::Success) return false;
  GearMassesState next = state_;
  store(posterior.solve(prior.solve(mean(state_)) + au), posterior.solve(Matrix::Identity(n, n)),
        &next);
  ++next.drives;
  if (!implausible(next).empty()) return false;
  state_ = next;
  refresh_scale_factor();
  return true;
}

std::string LearntGearMasses::implausible(const GearMassesState& s) const {
  if (s.gears != state_.gears) {
    return "learnt gear masses for " + std::to_string(s.gears) + " gears, the config has " +
           std::to_string(state_.gears);
  }
  if (s.drives < 0) return "learnt gear masses' drive count out of range";
  if (!std::isfinite(s.reference_precision) || s.reference_precision < 0.0 ||
      !std::isfinite(s.reference_applied)) {
    return "learnt gear masses' reference out of range";
  }
  for (int i = 0; i < s.gears; ++i) {
    const double share = s.reference_share_per_kg[std::size_t(i)];
    if (!std::isfinite(share) || share < 0.0) {
      return "learnt gear masses' reference share of gear " + std::to_string(i + 1) +
             " out of range";
    }
    // A correction as large as the gear's whole configured mass is no inertia error.
    const double c = s.correction_kg[std::size_t(i)];
    if (!std::isfinite(c) || std::abs(c) > config_kg_[std::size_t(i)]) {
      return "learnt correction of gear " + std::to_string(i + 1) + " (" + std::to_string(c) +
             " kg) beyond the gear's configured mass";
    }
    for (int j = 0; j < s.gears; ++j) {
      const double v = s.covariance_kg2[cell(i, j)];
      if (!std::isfinite(v) || v != s.covariance_kg2[cell(j, i)]) {
        return "learnt gear masses' covariance not finite and symmetric";
      }
    }
    const double var = s.covariance_kg2[cell(i, i)];
    if (!(var > 0.0) || var > 4.0 * prior_variance_kg2(i, i) + 1.0) {
      return "learnt gear masses' variance of gear " + std::to_string(i + 1) + " out of range";
    }
  }
  // The level the scale holds is a few per cent of the mass, as the rotating masses are.
  if (std::abs(reference_level(s)) > kMaxReferenceLevel) {
    return "learnt gear masses' reference level " + std::to_string(reference_level(s)) +
           " beyond its bound";
  }
  if (s.gears > 0 && covariance(s).llt().info() != Eigen::Success) {
    return "learnt gear masses' covariance not positive definite";
  }
  return "";
}

LearntGearMasses learnt_gear_masses_for(const VehicleParams& vehicle,
                                        const LearningParams& learning,
                                        double model_error_std_fraction) {
  const bool learns = learning.learn_gear_masses && !vehicle.derive_overall_ratio;
  return LearntGearMasses(learns ? vehicle.rotating_mass_by_gear_kg : std::vector<double>{},
                          vehicle.rotating_mass_accuracy_fraction, model_error_std_fraction,
                          learning.min_gear_evidence_pairs);
}

bool LearntGearMasses::restore(const GearMassesState& s) {
  if (!implausible(s).empty()) return false;
  state_ = s;
  refresh_scale_factor();
  return true;
}

}  // namespace vmass

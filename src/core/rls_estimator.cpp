#include "vmass/core/rls_estimator.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Eigenvalues>
#include <boost/math/distributions/normal.hpp>

#include "vmass/core/param_check.hpp"

namespace vmass {
namespace {

bool pair_is_usable(const RegressionPair& pair) {
  return std::isfinite(pair.y_n) && std::isfinite(pair.delta_accel_mps2) &&
         std::isfinite(pair.weight) && pair.weight > 0.0 && pair.information > 0.0 &&
         pair.information <= 1.0;
}

}  // namespace

std::string RlsParams::validate() const {
  ParamCheck c("rls");
  c.positive("noise_std_n", noise_std_n);
  c.in_half_open_range("forgetting_factor", forgetting_factor, 0.9, 1.0);
  c.in_open_range("min_variance_fraction", min_variance_fraction, 0.0, 1.0);
  return c.message();
}

RlsEstimator::RlsEstimator(const RlsParams& params)
    : params_(params),
      noise_var_n2_(params.noise_std_n * params.noise_std_n),
      z_(boost::math::quantile(boost::math::normal_distribution<double>(0.0, 1.0), 0.975)) {}

void RlsEstimator::reset(const MassPrior& prior) {
  theta_ << prior.mass_kg, prior.mu_n;
  p_max_.setZero();
  p_max_(0, 0) = prior.mass_std_kg * prior.mass_std_kg;
  p_max_(1, 1) = prior.mu_std_n * prior.mu_std_n;
  p_ = p_max_;
  pairs_used_ = 0;
}

void RlsEstimator::condition(Eigen::Matrix2d& p) const {
  const double off = 0.5 * (p(0, 1) + p(1, 0));
  p(0, 1) = off;
  p(1, 0) = off;
  // Prior-whitened coordinates: q = D^-1 p D^-1, D = diag(prior stds).
  const double s0 = std::sqrt(p_max_(0, 0));
  const double s1 = std::sqrt(p_max_(1, 1));
  Eigen::Matrix2d q;
  q(0, 0) = p(0, 0) / (s0 * s0);
  q(1, 1) = p(1, 1) / (s1 * s1);
  q(0, 1) = off / (s0 * s1);
  q(1, 0) = q(0, 1);
  // Eigenvalues of a symmetric 2x2 in closed form; the absolute error (~1e-16 of the largest,
  // which is <= 1 after clipping) is far below the lower bound.
  const double half_trace = 0.5 * (q(0, 0) + q(1, 1));
  const double radius = std::hypot(0.5 * (q(0, 0) - q(1, 1)), q(0, 1));
  const double lo = params_.min_variance_fraction;
  if (half_trace - radius >= lo && half_trace + radius <= 1.0) return;  // inside the bound

  Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig;
  eig.computeDirect(q);
  const Eigen::Vector2d clipped = eig.eigenvalues().cwiseMax(lo).cwiseMin(1.0);
  const Eigen::Matrix2d& v = eig.eigenvectors();
  q = v * clipped.asDiagonal() * v.transpose();
  p(0, 0) = q(0, 0) * s0 * s0;
  p(1, 1) = q(1, 1) * s1 * s1;
  p(0, 1) = 0.5 * (q(0, 1) + q(1, 0)) * s0 * s1;
  p(1, 0) = p(0, 1);
}

PairPrediction RlsEstimator::predict(const RegressionPair& pair) const {
  const Eigen::Vector2d phi(pair.delta_accel_mps2, 1.0);
  PairPrediction out;
  const double y = phi.dot(theta_);
  out.y_n = std::isfinite(y) ? y : 0.0;
  if (!pair_is_usable(pair)) {
    out.variance_n2 = std::numeric_limits<double>::infinity();
    return out;
  }
  const double variance =
      phi.dot(p_ * phi) + noise_var_n2_ / relative_weight(pair, std::sqrt(noise_var_n2_));
  out.variance_n2 = std::isfinite(variance) ? variance : std::numeric_limits<double>::infinity();
  return out;
}

bool RlsEstimator::update(const RegressionPair& pair) {
  if (!pair_is_usable(pair)) return false;
  const Eigen::Vector2d phi(pair.delta_accel_mps2, 1.0);
  // Precision of the pair as an observation among correlated neighbours (see RegressionPair).
  const double r =
      noise_var_n2_ / (relative_weight(pair, std::sqrt(noise_var_n2_)) * pair.information);
  const Eigen::Vector2d p_phi = p_ * phi;
  const double s = phi.dot(p_phi) + r;
  if (!(std::isfinite(s) && s > 0.0)) return false;
  const Eigen::Vector2d k = p_phi / s;
  const double innovation = pair.y_n - phi.dot(theta_);
  const Eigen::Vector2d theta = theta_ + k * innovation;
  const Eigen::Matrix2d a = Eigen::Matrix2d::Identity() - k * phi.transpose();
  Eigen::Matrix2d p = (a * p_ * a.transpose() + r * k * k.transpose()) / params_.forgetting_factor;
  if (!theta.allFinite() || !p.allFinite()) return false;
  condition(p);
  theta_ = theta;
  p_ = p;
  ++pairs_used_;
  return true;
}

RegressorState RlsEstimator::state() const {
  RegressorState out;
  out.mass_kg = theta_(0);
  out.mu_n = theta_(1);
  out.mass_std_kg = std::sqrt(p_(0, 0));
  out.mu_std_n = std::sqrt(p_(1, 1));
  out.ci_low_kg = out.mass_kg - z_ * out.mass_std_kg;
  out.ci_high_kg = out.mass_kg + z_ * out.mass_std_kg;
  out.noise_std_n = params_.noise_std_n;
  out.pairs_used = pairs_used_;
  return out;
}

bool RlsEstimator::restore(const Eigen::Vector2d& theta, const Eigen::Matrix2d& p,
                           long pairs_used) {
  if (!theta.allFinite() || !p.allFinite() || pairs_used < 0) return false;
  const double asym = std::abs(p(0, 1) - p(1, 0));
  const double det = p(0, 0) * p(1, 1) - p(0, 1) * p(1, 0);
  if (!(p(0, 0) > 0.0 && p(1, 1) > 0.0 && det > 0.0) ||
      asym > 1e-9 * std::sqrt(p(0, 0) * p(1, 1))) {
    return false;
  }
  Eigen::Matrix2d conditioned = p;
  condition(conditioned);
  theta_ = theta;
  p_ = conditioned;
  pairs_used_ = pairs_used;
  return true;
}

}  // namespace vmass

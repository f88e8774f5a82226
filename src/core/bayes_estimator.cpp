#include "vmass/core/bayes_estimator.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Cholesky>
#include <boost/math/distributions/normal.hpp>

#include "vmass/core/param_check.hpp"

namespace vmass {
namespace {

// Boost.Math reports errors through the policy instead of throwing: the core never throws.
using NoThrowPolicy = boost::math::policies::policy<
    boost::math::policies::domain_error<boost::math::policies::ignore_error>,
    boost::math::policies::pole_error<boost::math::policies::ignore_error>,
    boost::math::policies::overflow_error<boost::math::policies::ignore_error>,
    boost::math::policies::evaluation_error<boost::math::policies::ignore_error>>;

bool pair_is_usable(const RegressionPair& pair) {
  return std::isfinite(pair.y_n) && std::isfinite(pair.delta_accel_mps2) &&
         std::isfinite(pair.weight) && pair.weight > 0.0 && pair.information > 0.0 &&
         pair.information <= 1.0;
}

void symmetrise(Eigen::Matrix2d& m) {
  const double off = 0.5 * (m(0, 1) + m(1, 0));
  m(0, 1) = off;
  m(1, 0) = off;
}

bool is_spd(const Eigen::Matrix2d& m) {
  return m.allFinite() && m(0, 0) > 0.0 && m(1, 1) > 0.0 &&
         m(0, 0) * m(1, 1) - m(0, 1) * m(1, 0) > 0.0;
}

// The conjugate update in coordinates shifted by batch.origin (delta = theta - origin):
//   Lambda_n = V0^-1 + Phi^T W Phi,  delta_n = Lambda_n^-1 (V0^-1 delta_0 + Phi^T W e),
//   b_n = b0 + (e^T W e + delta_0^T V0^-1 delta_0 - delta_n^T Lambda_n delta_n) / 2,
// which is the header's update with y replaced by e = y - Phi origin (an exact identity).
bool try_conjugate_update(const NigPosterior& prior, const BayesEstimator::Sufficient& batch,
                          NigPosterior& out) {
  Eigen::Matrix2d v0 = prior.scaled_covariance;
  symmetrise(v0);
  if (!is_spd(v0) || !prior.mean.allFinite() || !batch.origin.allFinite()) return false;
  const Eigen::LDLT<Eigen::Matrix2d> v0_ldlt(v0);
  if (v0_ldlt.info() != Eigen::Success || !v0_ldlt.isPositive()) return false;
  Eigen::Matrix2d lambda0 = v0_ldlt.solve(Eigen::Matrix2d::Identity());
  symmetrise(lambda0);
  const Eigen::Vector2d delta0 = prior.mean - batch.origin;
  const Eigen::Vector2d lambda0_delta0 = v0_ldlt.solve(delta0);

  Eigen::Matrix2d lambda_n = lambda0 + batch.phi_t_w_phi;
  symmetrise(lambda_n);
  const Eigen::LDLT<Eigen::Matrix2d> ln_ldlt(lambda_n);
  if (ln_ldlt.info() != Eigen::Success || !ln_ldlt.isPositive()) return false;
  const Eigen::Vector2d rhs = lambda0_delta0 + batch.phi_t_w_y;
  const Eigen::Vector2d delta_n = ln_ldlt.solve(rhs);
  Eigen::Matrix2d v_n = ln_ldlt.solve(Eigen::Matrix2d::Identity());
  symmetrise(v_n);

  // The quadratic form is a weighted sum of squares (>= 0); rounding must not make it negative.
  const double quad = batch.y_t_w_y + delta0.dot(lambda0_delta0) - delta_n.dot(rhs);
  NigPosterior next;
  next.mean = batch.origin + delta_n;
  next.scaled_covariance = v_n;
  next.shape = prior.shape + 0.5 * batch.effective_count;
  next.scale = prior.scale + 0.5 * std::max(quad, 0.0);
  if (!next.mean.allFinite() || !is_spd(next.scaled_covariance) ||
      !(std::isfinite(next.shape) && next.shape > 0.0) ||
      !(std::isfinite(next.scale) && next.scale > 0.0)) {
    return false;
  }
  out = next;
  return true;
}

}  // namespace

std::string BayesParams::validate() const {
  ParamCheck c("bayes");
  c.at_least("batch_size", batch_size, 1.0);
  c.positive("noise_std_guess_n", noise_std_guess_n);
  c.positive("prior_noise_dof", prior_noise_dof);
  c.in_open_range("credible_level", credible_level, 0.0, 1.0);
  return c.message();
}

void BayesEstimator::Sufficient::add(const RegressionPair& pair) {
  if (!pair_is_usable(pair)) return;
  const Eigen::Vector2d phi(pair.delta_accel_mps2, 1.0);
  const double e = pair.y_n - phi.dot(origin);
  const double w = relative_weight(pair, reference_noise_n) * pair.information;
  phi_t_w_phi.noalias() += w * phi * phi.transpose();
  phi_t_w_y += (w * e) * phi;
  y_t_w_y += w * e * e;
  effective_count += pair.information;
  ++count;
}

NigPosterior BayesEstimator::conjugate_update(const NigPosterior& prior, const Sufficient& batch) {
  NigPosterior out;
  return try_conjugate_update(prior, batch, out) ? out : prior;
}

BayesEstimator::BayesEstimator(const BayesParams& params)
    : params_(params),
      z_q_(boost::math::quantile(boost::math::normal_distribution<double, NoThrowPolicy>(0.0, 1.0),
                                 0.5 * (1.0 + params.credible_level))),
      quantiles_(std::make_shared<StudentTQuantiles>(0.5 * (1.0 + params.credible_level))) {
  clear_pending();
  refresh();
}

void BayesEstimator::reset(const MassPrior& prior) {
  const double s2 = params_.noise_std_guess_n * params_.noise_std_guess_n;
  const double a0 = 0.5 * params_.prior_noise_dof;
  NigPosterior p;
  p.mean << prior.mass_kg, prior.mu_n;
  p.scaled_covariance.setZero();
  p.scaled_covariance(0, 0) = prior.mass_std_kg * prior.mass_std_kg / s2;
  p.scaled_covariance(1, 1) = prior.mu_std_n * prior.mu_std_n / s2;
  p.shape = a0;
  p.scale = a0 > 1.0 ? (a0 - 1.0) * s2 : a0 * s2;
  posterior_ = p;
  pairs_used_ = 0;
  clear_pending();
  refresh();
}

void BayesEstimator::clear_pending() {
  pending_ = Sufficient{};
  pending_.origin = posterior_.mean;
  pending_.reference_noise_n = params_.noise_std_guess_n;
  pending_count_ = 0;
}

void BayesEstimator::refresh() {
  const double t = quantiles_->at(2.0 * posterior_.shape);
  // Only reachable with invalid parameters or a posterior Boost cannot handle: the normal
  // quantile is the t quantile's limit.
  t_q_ = std::isfinite(t) && t > 0.0 ? t : z_q_;
}

PairPrediction BayesEstimator::predict(const RegressionPair& pair) const {
  const Eigen::Vector2d phi(pair.delta_accel_mps2, 1.0);
  PairPrediction out;
  const double y = phi.dot(posterior_.mean);
  out.y_n = std::isfinite(y) ? y : 0.0;
  if (!pair_is_usable(pair)) {
    out.variance_n2 = std::numeric_limits<double>::infinity();
    return out;
  }
  const double spread = 1.0 / relative_weight(pair, params_.noise_std_guess_n) +
                        phi.dot(posterior_.scaled_covariance * phi);
  const double a = posterior_.shape;
  const double b = posterior_.scale;
  double variance = 0.0;
  if (a > 1.0) {
    variance = b / (a - 1.0) * spread;
  } else {
    const double ratio = t_q_ / z_q_;
    variance = b / a * spread * ratio * ratio;
  }
  out.variance_n2 = std::isfinite(variance) ? variance : std::numeric_limits<double>::infinity();
  return out;
}

bool BayesEstimator::update(const RegressionPair& pair) {
  if (!pair_is_usable(pair)) return false;
  pending_.add(pair);
  ++pending_count_;
  if (pending_count_ < params_.batch_size) return false;
  return absorb_pending();
}

bool BayesEstimator::flush() { return pending_count_ > 0 && absorb_pending(); }

bool BayesEstimator::absorb_pending() {
  NigPosterior next;
  const bool ok = try_conjugate_update(posterior_, pending_, next);
  if (ok) {
    posterior_ = next;
    pairs_used_ += pending_.count;
  }
  clear_pending();
  if (ok) refresh();
  return ok;
}

RegressorState BayesEstimator::state() const {
  const NigPosterior& p = posterior_;
  const double a = p.shape;
  const double b = p.scale;
  // Variance factor of the marginal t when it exists, else the squared t scale factor.
  const double spread = a > 1.0 ? b / (a - 1.0) : b / a;
  RegressorState out;
  out.mass_kg = p.mean(0);
  out.mu_n = p.mean(1);
  out.mass_std_kg = std::sqrt(spread * p.scaled_covariance(0, 0));
  out.mu_std_n = std::sqrt(spread * p.scaled_covariance(1, 1));
  const double half_width = t_q_ * std::sqrt(b / a * p.scaled_covariance(0, 0));
  out.ci_low_kg = out.mass_kg - half_width;
  out.ci_high_kg = out.mass_kg + half_width;
  out.noise_std_n = std::sqrt(spread);
  out.pairs_used = pairs_used_;
  return out;
}

bool BayesEstimator::restore(const NigPosterior& posterior, long pairs_used) {
  const Eigen::Matrix2d& v = posterior.scaled_covariance;
  if (!posterior.mean.allFinite() || !is_spd(v) ||
      std::abs(v(0, 1) - v(1, 0)) > 1e-9 * std::sqrt(v(0, 0) * v(1, 1)) ||
      !(std::isfinite(posterior.shape) && posterior.shape > 0.0) ||
      !(std::isfinite(posterior.scale) && posterior.scale > 0.0) || pairs_used < 0) {
    return false;
  }
  posterior_ = posterior;
  symmetrise(posterior_.scaled_covariance);
  pairs_used_ = pairs_used;
  clear_pending();
  refresh();
  return true;
}

}  // namespace vmass

#include "vmass/core/lag_estimator.hpp"

#include <algorithm>
#include <cmath>

#include "vmass/core/param_check.hpp"

namespace vmass {

std::string LagParams::validate() const {
  ParamCheck c("estimator.longitudinal.lag");
  c.in_half_open_range("max_lag_s", max_lag_s, 0.0, 1.0);
  c.positive("memory_s", memory_s);
  c.in_open_range("min_correlation", min_correlation, 0.0, 1.0);
  c.non_negative("min_evidence_s", min_evidence_s);
  if (fixed_lag_s > max_lag_s) c.fail("fixed_lag_s", "must be at most max_lag_s");
  c.non_negative("provisional_std_s", provisional_std_s);
  return c.message();
}

LagEstimator::LagEstimator(const LagParams& params, double tick_rate_hz)
    : params_(params),
      rate_hz_(tick_rate_hz),
      forget_(std::exp(-1.0 / (params.memory_s * tick_rate_hz))),
      max_lag_(params.enabled || params.fixed_lag_s >= 0.0
                   ? static_cast<int>(std::lround(params.max_lag_s * tick_rate_hz))
                   : 0),
      s_ay_(static_cast<std::size_t>(max_lag_ + 1), 0.0),
      s_yy_(static_cast<std::size_t>(max_lag_ + 1), 0.0) {
  reset();
}

void LagEstimator::reset() {
  std::fill(s_ay_.begin(), s_ay_.end(), 0.0);
  std::fill(s_yy_.begin(), s_yy_.end(), 0.0);
  s_aa_ = evidence_s_ = 0.0;
  identified_ = params_.fixed_lag_s >= 0.0;
  lag_s_ = identified_ ? params_.fixed_lag_s : 0.0;
}

void LagEstimator::keep_as_prior() {
  if (!identified_ || params_.fixed_lag_s >= 0.0) {
    reset();
    return;
  }
  // The sums hold at most memory_s of pairs (their forgetting).
  const double held_s = std::min(evidence_s_, params_.memory_s);
  if (held_s <= params_.min_evidence_s) return;
  const double keep = params_.min_evidence_s / held_s;
  for (double& s : s_ay_) s *= keep;
  for (double& s : s_yy_) s *= keep;
  s_aa_ *= keep;
  evidence_s_ = params_.min_evidence_s;
}

void LagEstimator::add(double delta_accel_mps2, const double* y_by_lag) {
  if (max_lag_ == 0 || params_.fixed_lag_s >= 0.0) return;
  s_aa_ = forget_ * s_aa_ + delta_accel_mps2 * delta_accel_mps2;
  for (int lag = 0; lag <= max_lag_; ++lag) {
    const auto i = static_cast<std::size_t>(lag);
    s_ay_[i] = forget_ * s_ay_[i] + delta_accel_mps2 * y_by_lag[i];
    s_yy_[i] = forget_ * s_yy_[i] + y_by_lag[i] * y_by_lag[i];
  }
  evidence_s_ += 1.0 / rate_hz_;
  update_estimate();
}

void LagEstimator::update_estimate() {
  if (evidence_s_ < params_.min_evidence_s) return;
  double correlation = 0.0;
  const double lag_s = peak_lag_s(&correlation);
  if (correlation < params_.min_correlation) return;
  lag_s_ = lag_s;
  identified_ = true;
}

double LagEstimator::best_lag_s() const {
  if (identified_ || max_lag_ == 0 || !(s_aa_ > 0.0)) return lag_s_;
  double correlation = 0.0;
  return peak_lag_s(&correlation);
}

double LagEstimator::peak_lag_s(double* correlation) const {
  auto rho = [&](int lag) {
    const auto i = static_cast<std::size_t>(lag);
    const double d = std::sqrt(s_aa_ * s_yy_[i]);
    return d > 0.0 ? s_ay_[i] / d : 0.0;
  };
  int best = 0;
  for (int lag = 1; lag <= max_lag_; ++lag) {
    if (rho(lag) > rho(best)) best = lag;
  }
  const double peak = rho(best);
  // Parabola through the peak and its neighbours: the vertex, within half a tick.
  double offset = 0.0;
  if (best > 0 && best < max_lag_) {
    const double l = rho(best - 1);
    const double r = rho(best + 1);
    const double curvature = l - 2.0 * peak + r;
    if (curvature < 0.0) offset = std::clamp(0.5 * (l - r) / curvature, -0.5, 0.5);
  }
  *correlation = peak;
  return (static_cast<double>(best) + offset) / rate_hz_;
}

double LagEstimator::y_at(const double* y_by_lag, double lag_s) const {
  const double ticks = std::clamp(lag_s * rate_hz_, 0.0, static_cast<double>(max_lag_));
  const auto low = static_cast<int>(std::floor(ticks));
  const int high = std::min(low + 1, max_lag_);
  const double frac = ticks - static_cast<double>(low);
  return (1.0 - frac) * y_by_lag[static_cast<std::size_t>(low)] +
         frac * y_by_lag[static_cast<std::size_t>(high)];
}

}  // namespace vmass

#include "vmass/core/driveline_mode.hpp"

#include <algorithm>
#include <cmath>

#include "vmass/core/param_check.hpp"

namespace vmass {

namespace {

constexpr double kWarmUpS = 1.0;         ///< band-pass transients after a restart
constexpr double kIdentifyEveryS = 1.0;  ///< how often a gear's evidence is re-read
constexpr double kLagStepS = 0.02;       ///< the lag grid

}  // namespace

std::string DrivelineModeParams::validate() const {
  ParamCheck c("estimator.longitudinal.driveline_mode");
  c.positive("min_hz", min_hz);
  if (!(max_hz > min_hz)) c.fail("max_hz", "must be > min_hz");
  if (!(candidates >= 2 && candidates <= 64)) c.fail("candidates", "must be in [2, 64]");
  c.in_half_open_range("damping_ratio", damping_ratio, 0.0, 1.0);
  c.positive("band_low_hz", band_low_hz);
  if (!(band_high_hz > band_low_hz)) c.fail("band_high_hz", "must be > band_low_hz");
  c.non_negative("max_lag_s", max_lag_s);
  if (max_lag_s > 0.5) c.fail("max_lag_s", "must be <= 0.5");
  c.non_negative("min_evidence_s", min_evidence_s);
  c.in_open_range("min_correlation", min_correlation, 0.0, 1.0);
  c.non_negative("min_correlation_gain", min_correlation_gain);
  return c.message();
}

DrivelineMode::DrivelineMode(const DrivelineModeParams& params, double tick_rate_hz)
    : params_(params),
      rate_hz_(tick_rate_hz),
      max_lag_(static_cast<int>(std::lround(params.max_lag_s * tick_rate_hz))),
      lag_step_(std::max(1, static_cast<int>(std::lround(kLagStepS * tick_rate_hz)))),
      force_high_(
          SecondOrderSection::high_pass(params.band_low_hz, kButterworthDamping, tick_rate_hz)),
      // Below the Nyquist frequency whatever the tick rate.
      force_low_(SecondOrderSection::low_pass(std::min(params.band_high_hz, 0.45 * tick_rate_hz),
                                              kButterworthDamping, tick_rate_hz)),
      accel_high_(force_high_),
      accel_low_(force_low_) {
  const double nyquist_margin = 0.4 * tick_rate_hz;
  for (int i = 0; i < params.candidates; ++i) {
    const double f = params.min_hz * std::pow(params.max_hz / params.min_hz,
                                              static_cast<double>(i) / (params.candidates - 1));
    if (f >= nyquist_margin) break;
    candidate_hz_.push_back(f);
    candidate_modes_.push_back(SecondOrderSection::low_pass(f, params.damping_ratio, tick_rate_hz));
  }
  history_.assign(static_cast<std::size_t>(max_lag_ + 1) * candidate_count(), 0.0);
  best_fit_.assign(candidate_count(), -1.0);
  const std::size_t lags = lag_count();
  for (GearEvidence& g : gears_) {
    g.s_xa.assign(candidate_count() * lags, 0.0);
    g.s_xx.assign(candidate_count() * lags, 0.0);
  }
}

void DrivelineMode::restart() {
  primed_ = 0;
  applied_primed_ = false;
}

void DrivelineMode::reset() {
  restart();
  for (GearEvidence& g : gears_) {
    g.ticks = 0;
    g.s_aa = 0.0;
    std::fill(g.s_xa.begin(), g.s_xa.end(), 0.0);
    std::fill(g.s_xx.begin(), g.s_xx.end(), 0.0);
    g.mode_hz = 0.0;
  }
}

void DrivelineMode::observe(double force_n, double accel_x_mps2, int gear, bool clean) {
  if (!params_.enabled) return;
  if (primed_ == 0) {
    force_high_.settle(force_n, 0.0);
    accel_high_.settle(accel_x_mps2, 0.0);
    force_low_.settle(0.0, 1.0);
    accel_low_.settle(0.0, 1.0);
    for (SecondOrderSection& m : candidate_modes_) m.settle(0.0, 1.0);
  }
  ++primed_;
  const double force = force_low_.step(force_high_.step(force_n));
  const double accel = accel_low_.step(accel_high_.step(accel_x_mps2));
  const std::size_t n = candidate_count();
  head_ = (head_ + 1) % (max_lag_ + 1);
  double* now = &history_[static_cast<std::size_t>(head_) * n];
  for (std::size_t c = 0; c + 1 < n; ++c) now[c] = candidate_modes_[c].step(force);
  now[n - 1] = force;  // "none"

  if (!clean || gear < 1 || gear > kMaxGears) return;
  if (static_cast<double>(primed_) < std::max(kWarmUpS, params_.max_lag_s) * rate_hz_) return;
  GearEvidence& g = gears_[static_cast<std::size_t>(gear)];
  ++g.ticks;
  g.s_aa += accel * accel;
  const std::size_t lags = lag_count();
  for (std::size_t l = 0; l < lags; ++l) {
    const int slot = (head_ - static_cast<int>(l) * lag_step_ + (max_lag_ + 1)) % (max_lag_ + 1);
    const double* then = &history_[static_cast<std::size_t>(slot) * n];
    for (std::size_t c = 0; c < n; ++c) {
      g.s_xa[c * lags + l] += then[c] * accel;
      g.s_xx[c * lags + l] += then[c] * then[c];
    }
  }
  const long every = std::max(1L, std::lround(kIdentifyEveryS * rate_hz_));
  if (static_cast<double>(g.ticks) >= params_.min_evidence_s * rate_hz_ && g.ticks % every == 0) {
    identify(g);
  }
}

void DrivelineMode::identify(GearEvidence& g) {
  const std::size_t n = candidate_count();
  const std::size_t lags = lag_count();
  std::vector<double>& best_by_candidate = best_fit_;  // no allocation per tick
  std::fill(best_by_candidate.begin(), best_by_candidate.end(), -1.0);
  for (std::size_t c = 0; c < n; ++c) {
    for (std::size_t l = 0; l < lags; ++l) {
      const double norm = std::sqrt(g.s_xx[c * lags + l] * g.s_aa);
      if (!(norm > 0.0)) continue;
      best_by_candidate[c] = std::max(best_by_candidate[c], g.s_xa[c * lags + l] / norm);
    }
  }
  const std::size_t modes = n - 1;
  const auto best = std::max_element(best_by_candidate.begin(),
                                     best_by_candidate.begin() + static_cast<long>(modes));
  const std::size_t i = static_cast<std::size_t>(best - best_by_candidate.begin());
  const double none = best_by_candidate[n - 1];
  if (*best < params_.min_correlation || *best < none + params_.min_correlation_gain) {
    g.mode_hz = 0.0;
    return;
  }
  double log_f = std::log(candidate_hz_[i]);
  if (i > 0 && i + 1 < modes) {
    // A parabola through the peak and its neighbours, on the log grid's even steps.
    const double lo = best_by_candidate[i - 1];
    const double hi = best_by_candidate[i + 1];
    const double curvature = lo - 2.0 * *best + hi;
    if (curvature < 0.0) {
      const double step = std::log(candidate_hz_[i + 1]) - log_f;
      log_f += std::clamp(0.5 * (lo - hi) / curvature, -0.5, 0.5) * step;
    }
  }
  g.mode_hz = std::exp(log_f);
}

double DrivelineMode::mode_hz(int gear) const {
  if (gear < 1 || gear > kMaxGears) return 0.0;
  return gears_[static_cast<std::size_t>(gear)].mode_hz;
}

double DrivelineMode::hub_force_n(double force_n, int gear) {
  const double f = params_.enabled ? mode_hz(gear) : 0.0;
  if (!(f > 0.0)) {
    applied_primed_ = false;
    return force_n;
  }
  if (f != applied_hz_) {
    // A new gear (or a refined f_n): new coefficients, the shaft's state carried over.
    const SecondOrderSection c = SecondOrderSection::low_pass(f, params_.damping_ratio, rate_hz_);
    applied_.b0 = c.b0;
    applied_.b1 = c.b1;
    applied_.b2 = c.b2;
    applied_.a1 = c.a1;
    applied_.a2 = c.a2;
    applied_hz_ = f;
  }
  if (!applied_primed_) {
    applied_.settle(force_n, 1.0);
    applied_primed_ = true;
  }
  return applied_.step(force_n);
}

}  // namespace vmass

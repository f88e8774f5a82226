#include "vmass/core/learnt_scale.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "vmass/core/param_check.hpp"

namespace vmass {
namespace {

/// A saved belief wider than this many times the datasheet's (plus one) is refused.
constexpr double kMaxVarianceOverPrior = 4.0;

}  // namespace

std::string LearningParams::validate() const {
  ParamCheck c("estimator.learning");
  c.non_negative("drift_std_per_drive", drift_std_per_drive);
  c.positive("outlier_sigma", outlier_sigma);
  c.at_least("min_evidence_pairs", static_cast<double>(min_evidence_pairs), 1.0);
  c.positive("max_evidence_std_fraction", max_evidence_std_fraction);
  c.positive("anchor_prior_std_fraction", anchor_prior_std_fraction);
  c.in_open_range("max_abs_log_scale", max_abs_log_scale, 0.0, 1.0);
  c.non_negative("drive_error_std_fraction", drive_error_std_fraction);
  c.at_least("min_gear_evidence_pairs", static_cast<double>(min_gear_evidence_pairs), 1.0);
  c.in_open_range("tyre_change_std_fraction", tyre_change_std_fraction, 0.0, 0.2);
  c.nested(tyre_watch.validate());
  return c.message();
}

double declared_scale_variance(const VehicleParams& v) {
  constexpr double kUniformStdPerBound = 0.5773502691896258;  // std = bound / sqrt(3)
  constexpr double kRadPerDeg = 3.14159265358979323846 / 180.0;
  // A derived ratio's efficiency is nobody's datasheet figure: it scales the torque as its
  // accuracy does.
  const double efficiency =
      v.derive_overall_ratio ? kUniformStdPerBound * v.driveline_efficiency_accuracy_fraction : 0.0;
  return std::pow(kUniformStdPerBound * v.wheel_torque_accuracy_fraction, 2) +
         std::pow(kUniformStdPerBound * v.wheel_radius_accuracy_fraction, 2) +
         std::pow(kRadPerDeg * v.pitch_gradient_std_deg_per_g, 2) + efficiency * efficiency;
}

LearntScale::LearntScale(const LearningParams& params, double prior_std)
    : params_(params), prior_var_(std::max(prior_std * prior_std, 1e-10)) {
  reset();
}

double LearntScale::anchor_mean() const {
  return state_.anchor_weighted_log_scale / state_.anchor_weight;
}

double LearntScale::anchor_var() const {
  const double common = state_.anchor_weighted_common_std / state_.anchor_weight;
  return 1.0 / state_.anchor_weight + common * common;
}

// The anchors join the belief only while no known mass informs it (none since the last tyres):
// their shared error (the kerb mass, where the payload sits) is as large as what they measure,
// and a known mass measures kappa without it. Joined to a known mass's belief they only pulled it
// towards that error (cars with the sensor, drives 5-9: median 0.66 -> 0.78 %, p90 1.98 ->
// 2.58 %).
bool LearntScale::anchors_join() const {
  return state_.anchors > 0 && state_.evidence_since_tyres == 0;
}

double LearntScale::log_scale() const {
  if (!anchors_join()) return state_.log_scale;
  const double w_known = 1.0 / state_.log_scale_var;
  const double w_anchor = 1.0 / anchor_var();
  return (w_known * state_.log_scale + w_anchor * anchor_mean()) / (w_known + w_anchor);
}

double LearntScale::log_scale_var() const {
  if (!anchors_join()) return state_.log_scale_var;
  return 1.0 / (1.0 / state_.log_scale_var + 1.0 / anchor_var());
}

double LearntScale::scale() const { return std::exp(log_scale()); }

double LearntScale::relative_std() const { return std::sqrt(log_scale_var()); }

void LearntScale::reset() {
  state_ = LearntScaleState{};
  state_.log_scale_var = prior_var_;
}

void LearntScale::drift() {
  state_.log_scale_var += params_.drift_std_per_drive * params_.drift_std_per_drive;
}

void LearntScale::tyres_changed() {
  const double tyres2 = params_.tyre_change_std_fraction * params_.tyre_change_std_fraction;
  // What the anchors added to the belief stays in it, as wide as it was before the widening.
  // Never wider than the datasheet's belief with one change: a belief restore() takes, however
  // often it is declared.
  const double mean = log_scale();
  const double before = log_scale_var();
  const double var = std::max(before, std::min(before + tyres2, prior_var_ + tyres2));
  const long tyre_changes = state_.tyre_changes;
  const long evidence = state_.evidence;
  const long changes = state_.changes;
  state_ = LearntScaleState{};
  state_.log_scale = mean;
  state_.log_scale_var = var;
  state_.evidence = evidence;
  state_.changes = changes;
  state_.tyre_changes = tyre_changes + 1;
}

// The anchors' mean moves with the rest; the step's variance (a few tenths of a per cent) is
// added to the known masses' belief only, small beside the anchors' shared error.
void LearntScale::tyres_measured(double log_step, double log_step_var) {
  if (!std::isfinite(log_step) || !(log_step_var >= 0.0) || !std::isfinite(log_step_var)) return;
  const double bound = params_.max_abs_log_scale;
  state_.log_scale = std::clamp(state_.log_scale + log_step, -bound, bound);
  state_.log_scale_var += log_step_var;
  state_.anchor_weighted_log_scale += log_step * state_.anchor_weight;
  if (state_.pending_outlier_sign != 0) state_.pending_log_scale += log_step;
}

void LearntScale::take(double log_scale, double variance) {
  // The normal-normal update of the belief in log kappa.
  const double gain = state_.log_scale_var / (state_.log_scale_var + variance);
  state_.log_scale += gain * (log_scale - state_.log_scale);
  state_.log_scale_var *= 1.0 - gain;
}

ScaleEvidence LearntScale::add_evidence(double log_scale, double variance) {
  if (!std::isfinite(log_scale) || !(variance > 0.0) || !std::isfinite(variance) ||
      std::abs(log_scale) > params_.max_abs_log_scale) {
    return ScaleEvidence::kRefused;
  }
  const double spread = std::sqrt(state_.log_scale_var + variance);
  const double z = (log_scale - state_.log_scale) / spread;
  const long side = z > 0.0 ? 1 : -1;
  if (std::abs(z) <= params_.outlier_sigma) {
    take(log_scale, variance);
    state_.pending_outlier_sign = 0;
    ++state_.evidence;
    ++state_.evidence_since_tyres;
    return ScaleEvidence::kTaken;
  }
  // A second outlier on the same side that agrees with the first: the car changed. The belief
  // restarts from the two (their weighted mean), as wide as they are.
  if (state_.pending_outlier_sign == side) {
    const double d = log_scale - state_.pending_log_scale;
    const double pair_spread = std::sqrt(variance + state_.pending_var);
    if (std::abs(d) <= params_.outlier_sigma * pair_spread) {
      const double w1 = 1.0 / state_.pending_var;
      const double w2 = 1.0 / variance;
      state_.log_scale = (w1 * state_.pending_log_scale + w2 * log_scale) / (w1 + w2);
      state_.log_scale_var = 1.0 / (w1 + w2);
      state_.pending_outlier_sign = 0;
      ++state_.changes;
      ++state_.evidence;
      ++state_.evidence_since_tyres;
      return ScaleEvidence::kChange;
    }
  }
  // Huber: the outlier is taken as if its variance put it at outlier_sigma.
  take(log_scale, taken_variance(log_scale, variance));
  state_.pending_outlier_sign = side;
  state_.pending_log_scale = log_scale;
  state_.pending_var = variance;
  ++state_.evidence;
  ++state_.evidence_since_tyres;
  return ScaleEvidence::kDownweighted;
}

ScaleEvidence LearntScale::add_anchor(double log_scale, double variance, double common_std) {
  if (!std::isfinite(log_scale) || !(variance > 0.0) || !std::isfinite(variance) ||
      !(common_std >= 0.0) || !std::isfinite(common_std) ||
      std::abs(log_scale) > params_.max_abs_log_scale) {
    return ScaleEvidence::kRefused;
  }
  // Judged against everything believed so far, as a known mass is.
  const double spread = std::sqrt(log_scale_var() + variance + common_std * common_std);
  const double z = std::abs(log_scale - this->log_scale()) / spread;
  double taken = variance;
  if (z > params_.outlier_sigma) {
    const double inflation = z / params_.outlier_sigma;
    taken = spread * spread * inflation * inflation - log_scale_var() - common_std * common_std;
  }
  const double w = 1.0 / taken;
  state_.anchor_weight += w;
  state_.anchor_weighted_log_scale += w * log_scale;
  state_.anchor_weighted_common_std += w * common_std;
  ++state_.anchors;
  return z > params_.outlier_sigma ? ScaleEvidence::kDownweighted : ScaleEvidence::kTaken;
}

double LearntScale::taken_variance(double log_scale, double variance) const {
  if (!std::isfinite(log_scale) || !(variance > 0.0) || !std::isfinite(variance) ||
      std::abs(log_scale) > params_.max_abs_log_scale) {
    return std::numeric_limits<double>::infinity();
  }
  const double z = (log_scale - state_.log_scale) / std::sqrt(state_.log_scale_var + variance);
  if (std::abs(z) <= params_.outlier_sigma) return variance;
  const double inflation = std::abs(z) / params_.outlier_sigma;
  return (state_.log_scale_var + variance) * inflation * inflation - state_.log_scale_var;
}

std::string LearntScale::implausible(const LearntScaleState& s) const {
  if (!std::isfinite(s.log_scale) || std::abs(s.log_scale) > params_.max_abs_log_scale) {
    return "learnt scale log " + std::to_string(s.log_scale) + " beyond its bound";
  }
  if (!(s.log_scale_var > 0.0) || !std::isfinite(s.log_scale_var) ||
      s.log_scale_var > kMaxVarianceOverPrior * prior_var_ + 1.0) {
    return "learnt scale variance " + std::to_string(s.log_scale_var) + " out of range";
  }
  if (s.evidence < 0 || s.changes < 0 || s.changes > s.evidence || s.tyre_changes < 0 ||
      s.evidence_since_tyres < 0 || s.evidence_since_tyres > s.evidence) {
    return "learnt scale counts out of range";
  }
  if (s.anchors < 0 || !(s.anchor_weight >= 0.0) || !std::isfinite(s.anchor_weight) ||
      !std::isfinite(s.anchor_weighted_log_scale) || !std::isfinite(s.anchor_weighted_common_std) ||
      (s.anchors > 0) != (s.anchor_weight > 0.0) ||
      (s.anchors > 0 &&
       (std::abs(s.anchor_weighted_log_scale / s.anchor_weight) > params_.max_abs_log_scale ||
        s.anchor_weighted_common_std < 0.0))) {
    return "learnt scale's static anchors out of range";
  }
  if (s.pending_outlier_sign < -1 || s.pending_outlier_sign > 1 ||
      !std::isfinite(s.pending_log_scale) || !std::isfinite(s.pending_var) ||
      (s.pending_outlier_sign != 0 && !(s.pending_var > 0.0))) {
    return "learnt scale's pending outlier out of range";
  }
  return "";
}

bool LearntScale::restore(const LearntScaleState& s) {
  if (!implausible(s).empty()) return false;
  state_ = s;
  return true;
}

}  // namespace vmass

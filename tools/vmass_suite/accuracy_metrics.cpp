#include "accuracy_metrics.hpp"

#include <algorithm>
#include <cmath>

namespace vmass::suite {

namespace {
constexpr double kDriveStartSpeedMps = 0.5;
}  // namespace

double TruthTrack::mass_at(TimeUs t) const {
  if (time_us.empty()) return AccuracyResult::kNaN;
  const auto it = std::upper_bound(time_us.begin(), time_us.end(), t);
  const std::size_t i =
      it == time_us.begin() ? 0 : static_cast<std::size_t>(it - time_us.begin()) - 1;
  return mass_kg[i];
}

TimeUs TruthTrack::drive_start_us() const {
  for (std::size_t i = 0; i < speed_mps.size(); ++i) {
    if (speed_mps[i] > kDriveStartSpeedMps) return time_us[i];
  }
  return time_us.empty() ? 0 : time_us.front();
}

AccuracyMetrics::AccuracyMetrics(const TruthTrack& truth)
    : truth_(truth), start_us_(truth.drive_start_us()) {
  errors_pct_.reserve(truth.time_us.size() + 16);
}

void AccuracyMetrics::add(const EstimatePoint& p) {
  const double truth = truth_.mass_at(p.time_us);
  const double err = p.has_mass ? 100.0 * (p.mass_kg - truth) / truth : AccuracyResult::kNaN;
  const bool covers = p.has_mass && p.has_interval && p.ci_low_kg <= truth && truth <= p.ci_high_kg;
  errors_pct_.push_back(err);
  ++r_.ticks;
  for (std::size_t j = 0; j < kTolerancesPct.size(); ++j) {
    if (!(std::abs(err) <= kTolerancesPct[j])) {
      last_outside_us_[j] = p.time_us;
      ever_outside_[j] = true;
    }
  }
  for (std::size_t i = 0; i < kCheckpointsS.size(); ++i) {
    const TimeUs at = start_us_ + from_seconds(kCheckpointsS[i]);
    if (p.time_us >= at && std::isnan(r_.error_at_pct[i]) && r_.covered_at[i] == -1) {
      r_.error_at_pct[i] = err;
      r_.covered_at[i] = p.has_mass && p.has_interval ? (covers ? 1 : 0) : -1;
    }
  }
  if (p.converged) seen_converged_ = true;
  if (seen_converged_) {
    ++after_converged_;
    if (!covers) ++outside_after_converged_;
  }
  last_ = p;
  last_time_us_ = p.time_us;
}

AccuracyResult AccuracyMetrics::result() const {
  AccuracyResult r = r_;
  if (r.ticks == 0) return r;
  const double truth = truth_.mass_at(last_time_us_);
  r.true_final_mass_kg = truth;
  r.has_estimate = last_.has_mass;
  if (last_.has_mass) {
    r.final_mass_kg = last_.mass_kg;
    r.final_error_pct = 100.0 * (last_.mass_kg - truth) / truth;
    if (last_.has_interval) {
      r.covered_end = last_.ci_low_kg <= truth && truth <= last_.ci_high_kg ? 1 : 0;
      r.halfwidth_end_pct = 100.0 * 0.5 * (last_.ci_high_kg - last_.ci_low_kg) / truth;
    }
  }
  for (std::size_t j = 0; j < kTolerancesPct.size(); ++j) {
    const bool within_at_end = std::abs(r.final_error_pct) <= kTolerancesPct[j];
    if (!within_at_end) continue;
    r.time_within_s[j] =
        ever_outside_[j] ? std::max(0.0, to_seconds(last_outside_us_[j] - start_us_)) : 0.0;
  }
  const std::size_t half = errors_pct_.size() / 2;
  double sum = 0.0;
  std::size_t n = 0;
  for (std::size_t i = half; i < errors_pct_.size(); ++i) {
    if (std::isnan(errors_pct_[i])) continue;
    sum += errors_pct_[i] * errors_pct_[i];
    ++n;
  }
  if (n > 0) r.rms_last_half_pct = std::sqrt(sum / static_cast<double>(n));
  if (after_converged_ > 0) {
    r.converged_outside_fraction =
        static_cast<double>(outside_after_converged_) / static_cast<double>(after_converged_);
  }
  return r;
}

}  // namespace vmass::suite

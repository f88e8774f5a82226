#include "vmass/scoring/accuracy_metrics.hpp"

#include <algorithm>
#include <cmath>

#include "vmass/scoring/tick_comparison.hpp"

namespace vmass::scoring {

AccuracyMetrics::AccuracyMetrics(const Truth& truth)
    : truth_(truth), start_us_(truth.drive_start_us()) {
  errors_pct_.reserve(truth.size() + 16);
}

void AccuracyMetrics::add(const EstimatePoint& p) {
  const double truth = truth_.mass_at(p.time_us);
  const double err = p.has_mass ? error_pct(p.mass_kg, truth) : AccuracyResult::kNaN;
  const bool covers =
      p.has_mass && p.has_interval && interval_covers(p.ci_low_kg, p.ci_high_kg, truth);
  errors_pct_.push_back(err);
  ++r_.ticks;
  within_.add(p.time_us, std::abs(err));
  check_checkpoints(p, err, covers);
  if (p.converged) seen_converged_ = true;
  if (seen_converged_) {
    ++after_converged_;
    if (!covers) ++outside_after_converged_;
  }
  last_ = p;
  last_time_us_ = p.time_us;
}

void AccuracyMetrics::check_checkpoints(const EstimatePoint& p, double err, bool covers) {
  for (std::size_t i = 0; i < kCheckpointsS.size(); ++i) {
    const TimeUs at = start_us_ + from_seconds(kCheckpointsS[i]);
    if (p.time_us >= at && std::isnan(r_.error_at_pct[i]) && r_.covered_at_checkpoint[i] == -1) {
      r_.error_at_pct[i] = err;
      r_.covered_at_checkpoint[i] = p.has_mass && p.has_interval ? (covers ? 1 : 0) : -1;
    }
  }
}

AccuracyResult AccuracyMetrics::result() const {
  AccuracyResult r = r_;
  if (r.ticks == 0) return r;
  end_scores(&r);
  for (std::size_t j = 0; j < kToleranceCount; ++j) {
    const bool within_at_end = std::abs(r.final_error_pct) <= kTolerancesPct[j];
    if (!within_at_end) continue;
    const std::optional<TimeUs> outside = within_.last_outside_us(j);
    r.time_within_since_drive_start_s[j] =
        outside ? std::max(0.0, to_seconds(*outside - start_us_)) : 0.0;
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

// The scores of the last tick: its error, whether its interval covers the truth, its width.
void AccuracyMetrics::end_scores(AccuracyResult* r) const {
  const double truth = truth_.mass_at(last_time_us_);
  r->true_final_mass_kg = truth;
  r->has_estimate = last_.has_mass;
  if (!last_.has_mass) return;
  r->final_mass_kg = last_.mass_kg;
  r->final_error_pct = error_pct(last_.mass_kg, truth);
  if (!last_.has_interval) return;
  r->covered_at_end = interval_covers(last_.ci_low_kg, last_.ci_high_kg, truth) ? 1 : 0;
  r->halfwidth_end_pct = 100.0 * 0.5 * (last_.ci_high_kg - last_.ci_low_kg) / truth;
}

}  // namespace vmass::scoring

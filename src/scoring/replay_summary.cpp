#include "vmass/scoring/replay_summary.hpp"

#include <cmath>

#include "vmass/scoring/tick_comparison.hpp"

namespace vmass::scoring {

void ReplaySummary::add(const Estimate& e) {
  if (!started_) {
    started_ = true;
    first_us_ = e.time_us;
  }
  ++ticks_;
  if (has_last_ && e.initial_mass_kg != last_.initial_mass_kg && last_.has_mass()) {
    ++reinitialisations_;  // a new prior: load change
  }
  last_ = e;
  has_last_ = true;
  if (!e.has_mass()) return;
  if (!any_mass_) {
    any_mass_ = true;
    first_mass_us_ = e.time_us;
  }
  check_tolerances(e);
  if (truth_ && e.pairs_used > 0) {
    ++dynamic_ticks_;
    if (interval_covers(e.ci_low_kg, e.ci_high_kg, truth_->mass_at(e.time_us))) ++covered_ticks_;
  }
}

void ReplaySummary::finish(const Estimate& flushed) {
  if (!has_last_ || !flushed.has_mass()) return;
  last_ = flushed;
  check_tolerances(flushed);
}

void ReplaySummary::check_tolerances(const Estimate& e) {
  if (!truth_) return;
  const double truth = truth_->mass_at(e.time_us);
  const double rel = std::abs(e.mass_kg - truth) / truth;
  if (std::isnan(rel)) return;  // 0 kg against a 0 kg truth: the replay never called it outside
  within_.add(e.time_us, rel);
}

ReplaySummary::Result ReplaySummary::result() const {
  Result r;
  r.ticks = ticks_;
  r.reinitialisations = reinitialisations_;
  r.verdicts = verdicts_;
  r.learnt = learnt_;
  r.coarse_speed_interval_s = coarse_speed_interval_s_;
  r.pair_terms = pair_terms_;
  if (!has_last_) return r;
  r.duration_s = to_seconds(last_.time_us - first_us_);
  r.final_estimate = last_;
  r.has_estimate = any_mass_;
  for (const BlockCounters& c : last_.blocks) r.pairs_accepted += c.accepted;
  if (!truth_ || !any_mass_) return r;
  r.true_mass_kg = truth_->mass_at(last_.time_us);
  r.error_percent = error_pct(last_.mass_kg, *r.true_mass_kg);
  if (dynamic_ticks_ > 0) {
    r.coverage_of_dynamic_ticks =
        static_cast<double>(covered_ticks_) / static_cast<double>(dynamic_ticks_);
  }
  if (last_.pairs_used > 0) time_within(&r);  // the prior only: no "within" claim
  return r;
}

void ReplaySummary::time_within(Result* r) const {
  for (std::size_t i = 0; i < kToleranceCount; ++i) {
    const std::optional<TimeUs> outside = within_.last_outside_us(i);
    if (!outside) {
      r->time_within_since_first_tick_s[i] = to_seconds(first_mass_us_ - first_us_);
    } else if (*outside < last_.time_us) {
      r->time_within_since_first_tick_s[i] = to_seconds(*outside - first_us_);
    }
  }
}

void record_learnt(const Pipeline& pipeline, int known_masses, ReplaySummary* summary) {
  const LearntScale learnt = pipeline.learnt_scale_if_ended();
  const LearntGearMasses gears = pipeline.gear_masses_if_ended();
  if (known_masses == 0 && !learnt.learnt() && !gears.learnt()) return;
  ReplaySummary::Result::Learnt l;
  l.scale = learnt.scale();
  l.relative_std = learnt.relative_std();
  l.evidence = learnt.state().evidence;
  l.changes = learnt.state().changes;
  l.anchors = learnt.state().anchors;
  l.known_masses = known_masses;
  l.gear_drives = gears.state().drives;
  for (int g = 1; g <= gears.gears() && gears.learnt(); ++g) {
    l.gear_correction_kg.push_back(gears.correction_kg(g));
    l.gear_std_kg.push_back(gears.correction_std_kg(g));
  }
  summary->set_learnt(l);
}

void record_speed_signal(const Pipeline& pipeline, ReplaySummary* summary) {
  const LongitudinalExtractor& block = pipeline.longitudinal();
  if (block.speed_refresh().coarse() && !block.rotating_from_wheel_speed()) {
    summary->set_coarse_speed(block.speed_refresh().mean_interval_s());
  }
}

void record_pair_terms(const Pipeline& pipeline, ReplaySummary* summary) {
  if (const std::optional<PairTermFit> fit = pipeline.pair_term_fit())
    summary->set_pair_terms(*fit);
}

}  // namespace vmass::scoring

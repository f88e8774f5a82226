#include "vmass/core/pipeline.hpp"

#include <algorithm>
#include <cmath>

#include "vmass/core/load_change_odds.hpp"
#include "vmass/core/param_check.hpp"
#include "vmass/core/plausible_band.hpp"

namespace vmass {

namespace {

constexpr double kNormal95 = 1.959963984540054;  ///< the normal distribution's 97.5 % quantile

}  // namespace

std::string_view regressor_type_name(RegressorType t) {
  return t == RegressorType::kRls ? "rls" : "bayes";
}

std::string EstimatorParams::validate() const {
  ParamCheck c("estimator");
  c.nested(differencing.validate());
  if (differencing.validate().empty()) {
    c.nested(monitor_differencing().validate("estimator.load_change"));
  }
  c.nested(static_init.validate());
  c.nested(load_change.validate());
  c.nested(longitudinal.validate());
  c.nested(lateral.validate());
  c.nested(learning.validate());
  c.nested(supervisor.validate());
  c.nested(rls.validate());
  c.nested(bayes.validate());
  c.in_open_range("converged_ci_halfwidth_fraction", converged_ci_halfwidth_fraction, 0.0, 1.0);
  c.in_open_range("converged_halfwidth_fraction", converged_halfwidth_fraction, 0.0, 1.0);
  if (!(model_error_std_fraction >= 0.0 && model_error_std_fraction < 1.0)) {
    c.fail("model_error_std_fraction", "must be in [0, 1)");
  }
  c.positive("power_cycle_min_off_s", power_cycle_min_off_s);
  if (!(pair_correlation_ticks == 0.0 || pair_correlation_ticks >= 1.0)) {
    c.fail("pair_correlation_ticks", "must be 0 (automatic) or >= 1");
  }
  return c.message();
}

DifferencingParams EstimatorParams::monitor_differencing() const {
  DifferencingParams d = differencing;
  d.differencing_dt_s = load_change.differencing_dt_s;
  d.filter_cutoff_hz = load_change.filter_cutoff_hz;
  return d;
}

double EstimatorParams::effective_pair_correlation_ticks(const DifferencingParams& d) const {
  if (pair_correlation_ticks >= 1.0) return pair_correlation_ticks;
  // Pairs taken every tick share their noise with their neighbours for about the differencing
  // window (they difference overlapping stretches) plus the low-pass's time constant
  // 1 / (2 pi f_c), in ticks.
  constexpr double kTwoPi = 6.283185307179586;
  const double filter_ticks =
      d.filter_cutoff_hz > 0.0 ? d.tick_rate_hz / (kTwoPi * d.filter_cutoff_hz) : 0.0;
  return std::max(1.0, static_cast<double>(d.steps()) + filter_ticks);
}

std::string PipelineParams::validate() const {
  ParamCheck c("");
  c.nested(vehicle.validate());
  c.nested(suspension.validate());
  c.nested(estimator.validate());
  return c.message();
}

namespace {

// Declared bounds are of a uniform error (std = bound / sqrt(3)); the pitch's is a std already.
constexpr double kUniformStdPerBound = 0.5773502691896258;

/// A longitudinal pair in the belief's units: its force divided by the learnt scale (the pairs
/// read kappa M). Exactly the pair when the scale is 1.
void divide_force(RegressionPair* pair, double scale) {
  if (scale == 1.0) return;
  pair->y_n /= scale;
  pair->noise_std_n /= scale;
  pair->rotating_n /= scale;
  pair->converter_n /= scale;
}

}  // namespace

Pipeline::Pipeline(const PipelineParams& params)
    : params_(params),
      static_init_(params.vehicle, params.suspension, params.estimator.static_init),
      load_monitor_(params.estimator.load_change, params.estimator.rls, params.estimator.bayes,
                    params.estimator.supervisor, params.estimator.type == RegressorType::kRls,
                    static_init_.no_static_prior(), params.vehicle.empty_mass_kg,
                    params.estimator.static_init.standstill_speed_mps),
      longitudinal_(params.vehicle, params.estimator.longitudinal, params.estimator.differencing),
      lateral_(params.vehicle, params.estimator.lateral, params.estimator.differencing),
      monitor_longitudinal_(params.vehicle, params.estimator.longitudinal,
                            params.estimator.monitor_differencing()),
      monitor_lateral_(params.vehicle, params.estimator.lateral,
                       params.estimator.monitor_differencing()),
      supervisor_(params.estimator.supervisor),
      rls_(params.estimator.rls),
      bayes_(params.estimator.bayes),
      regressor_(params.estimator.type == RegressorType::kRls
                     ? static_cast<MassRegressor*>(&rls_)
                     : static_cast<MassRegressor*>(&bayes_)),
      rls_before_stop_(params.estimator.rls),
      bayes_before_stop_(params.estimator.bayes),
      rls_without_interlude_(params.estimator.rls),
      bayes_without_interlude_(params.estimator.bayes),
      pair_information_(
          1.0 / params.estimator.effective_pair_correlation_ticks(params.estimator.differencing)),
      monitor_pair_information_(1.0 / params.estimator.effective_pair_correlation_ticks(
                                          params.estimator.monitor_differencing())),
      learnt_(params.estimator.learning, std::sqrt(declared_scale_variance(params.vehicle))),
      gear_masses_(learnt_gear_masses_for(params.vehicle, params.estimator.learning,
                                          params.estimator.model_error_std_fraction)),
      applied_gear_masses_(gear_masses_),
      static_anchor_(params.estimator.bayes),
      tyre_watch_(params.estimator.learning.tyre_watch) {}

void Pipeline::publish_learnt_gears() {
  if (gear_masses_.revision() == published_gear_revision_) return;
  published_gear_revision_ = gear_masses_.revision();
  estimate_.learnt_gears = gear_masses_.gears();
  estimate_.learnt_gear_drives = gear_masses_.state().drives;
  for (int gear = 1; gear <= gear_masses_.gears(); ++gear) {
    const auto i = static_cast<std::size_t>(gear - 1);
    estimate_.learnt_gear_correction_kg[i] = gear_masses_.correction_kg(gear);
    estimate_.learnt_gear_std_kg[i] = gear_masses_.correction_std_kg(gear);
  }
}

void Pipeline::publish_tyre_watch() {
  if (tyre_watch_.revision() == published_tyre_revision_) return;
  published_tyre_revision_ = tyre_watch_.revision();
  const SpanSums held = tyre_watch_.held();
  estimate_.tyre_watch_launches = std::lround(held.kind[std::size_t(SpanKind::kLaunch)].count);
  estimate_.tyre_watch_stops = std::lround(held.kind[std::size_t(SpanKind::kStop)].count);
  estimate_.tyre_watch_changes = tyre_watch_.state().changes;
  const TyreVerdict& standing = tyre_watch_.standing();
  estimate_.tyre_watch_step = std::expm1(standing.log_step);
  estimate_.tyre_watch_step_sigma = standing.best_sigma;
  estimate_.tyre_watch_suspected = tyre_watch_.suspected_variance() > 0.0;
}

void Pipeline::publish_pair_term_fit() {
  const std::optional<PairTermFit> fit = pair_term_fit();
  estimate_.pair_fit_applies = fit.has_value();
  const PairTermFit shown = fit.value_or(PairTermFit{});
  estimate_.pair_fit_converter_multiplied = shown.converter_multiplied;
  estimate_.pair_fit_pairs = shown.pairs;
  estimate_.pair_fit_rotating_error = shown.rotating_error;
  estimate_.pair_fit_rotating_error_std = shown.rotating_error_std;
  estimate_.pair_fit_converter_error = shown.converter_error;
  estimate_.pair_fit_converter_error_std = shown.converter_error_std;
  estimate_.pair_fit_shift_kg = shown.mass_shift_kg;
  estimate_.pair_fit_shift_std_kg = shown.mass_std_kg;
}

double Pipeline::scale_for_pairs() const {
  return learnt_.scale() * applied_gear_masses_.scale_factor();
}

void Pipeline::to_belief_units(RegressionPair* pair) const {
  divide_force(pair, pair_scale_);
  if (GearPairSums::slot(*pair, applied_gear_masses_.gears()) < 0) return;
  pair->y_n -= applied_gear_masses_.correction_kg(pair->gear) * pair->wheel_delta_accel_mps2;
}

double Pipeline::uncorrected_y_n(const RegressionPair& pair) const {
  if (GearPairSums::slot(pair, applied_gear_masses_.gears()) < 0) return pair.y_n;
  return pair.y_n + applied_gear_masses_.correction_kg(pair.gear) * pair.wheel_delta_accel_mps2;
}

void Pipeline::reset_extractors(double reference_mass_kg) {
  // The extractors see the force before it is divided by the learnt scale.
  longitudinal_.set_reference_mass(reference_mass_kg * pair_scale_);
  longitudinal_.reset();
  lateral_.reset();
  monitor_longitudinal_.set_reference_mass(reference_mass_kg * pair_scale_);
  monitor_longitudinal_.reset();
  monitor_lateral_.reset();
}

void Pipeline::restart(const MassPrior& prior, StatusReason reason) {
  end_known_mass();
  before_stop_saved_ = false;
  interlude_pending_ = false;
  end_static_anchor();
  end_gear_evidence();
  pair_scale_ = scale_for_pairs();
  load_unchecked_ = false;
  regressor_->reset(prior);
  supervisor_.on_regressor_reset();
  reset_extractors(prior.mass_kg);
  decide_term_fit();
  has_prior_ = true;
  has_plausible_ = false;
  prior_reason_ = reason;
  prior_ = prior;
  estimate_.initial_mass_kg = prior.mass_kg;
  estimate_.prior_reason = reason;
}

void Pipeline::offer_pairs(const Sample& sample, StepResult* result) {
  // Extractors run on every tick (their filters need continuity); the supervisor decides.
  Extraction longitudinal = longitudinal_.step(sample);
  Extraction lateral = lateral_.step(sample);
  to_belief_units(&longitudinal.pair);
  longitudinal.pair.information = pair_information_;
  lateral.pair.information = pair_information_;
  if (longitudinal.has_pair()) add_to_sensitivities(longitudinal.pair);
  PairEvent& event = result->events[static_cast<int>(Block::kLongitudinal)];
  event =
      supervisor_.offer(Block::kLongitudinal, longitudinal, *regressor_, &result->estimate_changed);
  add_to_load_sums(longitudinal, event);
  // Pairs kept while the driveline lag was unknown, now at the identified lag.
  Extraction released;
  while (longitudinal_.pop_released(&released)) {
    to_belief_units(&released.pair);
    released.pair.information = pair_information_;
    if (released.has_pair()) add_to_sensitivities(released.pair);
    add_to_load_sums(released, supervisor_.offer_late(Block::kLongitudinal, released, *regressor_,
                                                      &result->estimate_changed));
  }
  result->events[static_cast<int>(Block::kLateral)] =
      supervisor_.offer(Block::kLateral, lateral, *regressor_, &result->estimate_changed);
}

// The extractors measure their noise as the spread of y about M_ref da. About the prior's mass
// (a truck's no-load-sensor prior is 24.7 t; its load 14-46 t) the spread is the prior's error
// times da, the gates let only the largest da through and every pair is weighed as noisy; so
// M_ref follows each extractor's own belief once that has pairs.
void Pipeline::follow_beliefs() {
  const RegressorState main = regressor_->state();
  if (main.pairs_used > 0 && main.mass_kg > 0.0) {
    longitudinal_.set_reference_mass(main.mass_kg * pair_scale_);
  }
  if (!load_monitor_.active()) return;
  const RegressorState challenger = load_monitor_.challenger().state();
  if (challenger.pairs_used > 0 && challenger.mass_kg > 0.0) {
    monitor_longitudinal_.set_reference_mass(challenger.mass_kg * pair_scale_);
  }
}

void Pipeline::add_to_sensitivities(const RegressionPair& pair) {
  rotating_sensitivity_.add(pair);
  converter_sensitivity_.add(pair);
  interval_sums_.add(pair, uncorrected_y_n(pair), gear_masses_.gears());
}

void Pipeline::add_to_load_sums(const Extraction& extraction, const PairEvent& event) {
  if (!extraction.has_pair() || event.verdict != PairVerdict::kAccepted) return;
  static_anchor_.add(extraction.pair);
  load_sums_.add(extraction.pair, uncorrected_y_n(extraction.pair), gear_masses_.gears());
  term_sums_.add(extraction.pair, params_.estimator.bayes.noise_std_guess_n);
  refit_terms();
}

// Only where the speed signal is the wheels' own and fresh (not a display's coarse, late
// speed) and the accelerometer is the one the pairs use.
void Pipeline::watch_launches(const Sample& sample) {
  LaunchSpan span;
  if (!launches_.step(sample, &span)) return;
  if (params_.estimator.longitudinal.accel_source != AccelSource::kAccelerometer ||
      !longitudinal_.rotating_from_wheel_speed()) {
    return;
  }
  tyre_watch_.add_span(span.stop ? SpanKind::kStop : SpanKind::kLaunch, span.accel_dv,
                       span.wheel_dv);
}

void Pipeline::end_tyre_watch() {
  const TyreVerdict verdict = tyre_watch_.end_drive();
  if (verdict.changed) learnt_.tyres_measured(verdict.log_step, verdict.log_step_var);
}

void Pipeline::end_gear_evidence() {
  if (has_prior_) {
    const RegressorState belief = belief_state();
    if (belief.pairs_used > 0) gear_masses_.add_evidence(load_sums_, belief.mass_kg, belief.mu_n);
  }
  clear_load_sums();
}

void Pipeline::clear_load_sums() {
  load_sums_ = GearPairSums{};
  sums_before_stop_ = GearPairSums{};
  term_sums_ = PairTermSums{};
  term_sums_before_stop_ = PairTermSums{};
  refit_terms();
}

LearntGearMasses Pipeline::gear_masses_if_ended() const {
  if (!has_prior_) return gear_masses_;
  const RegressorState belief = belief_state();
  if (belief.pairs_used == 0) return gear_masses_;
  LearntGearMasses out = gear_masses_;
  ScaleObservation seen;
  if (scale_observation(known_mass_, belief, params_.estimator.learning, &seen)) {
    out.add_reference(load_sums_, known_mass_.mass_kg,
                      learnt_.taken_variance(seen.log_scale, seen.variance),
                      declared_scale_variance(params_.vehicle), applied_gear_masses_);
  }
  out.add_evidence(load_sums_, belief.mass_kg, belief.mu_n);
  return out;
}

void Pipeline::offer_monitor_pairs(const Sample& sample) {
  // The challenger is judged against the belief as it was before the stop: the pairs since
  // then, of a load that may have changed, must not pull the reference towards the challenger.
  if (load_monitor_.step(sample)) {
    const bool returned = interlude_pending_ && judge_interlude();
    if (!returned && ended_drive_read_another_load()) hold_interlude();
    belief_before_stop_ = regressor_->state();
    sums_before_stop_ = load_sums_;
    term_sums_before_stop_ = term_sums_;
    copy_regressor(rls_, bayes_, &rls_before_stop_, &bayes_before_stop_);
    before_stop_saved_ = true;
    // The challenger's extractor starts as on a fresh drive, at the challenger's prior: its lag,
    // noise and reference mass of the load before would misread today's.
    monitor_longitudinal_.forget_load();
    monitor_longitudinal_.set_reference_mass(load_monitor_.start_prior().mass_kg * pair_scale_);
    // A belief no drive has informed yet (the prior alone) holds nothing a challenger could
    // contradict: the drive after this stop simply refines it.
    if (belief_before_stop_.pairs_used == 0) load_monitor_.dismiss();
  }
  Extraction longitudinal = monitor_longitudinal_.step(sample);
  Extraction lateral = monitor_lateral_.step(sample);
  to_belief_units(&longitudinal.pair);
  longitudinal.pair.information = monitor_pair_information_;
  lateral.pair.information = monitor_pair_information_;
  load_monitor_.offer(Block::kLongitudinal, longitudinal);
  load_monitor_.offer(Block::kLateral, lateral);
  Extraction released;
  while (monitor_longitudinal_.pop_released(&released)) {
    to_belief_units(&released.pair);
    released.pair.information = monitor_pair_information_;
    load_monitor_.offer(Block::kLongitudinal, released);
  }
}

// The drive between the last two long stops ended in a lasting suspicion (its challenger had
// its pairs, excluded the belief it was judged against and did not decide), and a change is the
// likelier reading of it (probability_load_changed, with both spreads and the model error they
// do not share). Then it most likely read another load, whether that load is still on or was
// unloaded at this stop. A suspicion a change does not explain better (a belief of few pairs
// against a sure drive, a part of a drive in other gears) is the same load: it is not held.
bool Pipeline::ended_drive_read_another_load() const {
  return before_stop_saved_ && load_monitor_.ended_in_suspicion(belief_before_stop_) &&
         probability_load_changed(load_monitor_.ended()) > 0.5;
}

// Only the kind in use: the other is never read.
void Pipeline::copy_regressor(const RlsEstimator& rls, const BayesEstimator& bayes,
                              RlsEstimator* rls_to, BayesEstimator* bayes_to) const {
  if (params_.estimator.type == RegressorType::kRls) {
    *rls_to = rls;
  } else {
    *bayes_to = bayes;
  }
}

// Mixed in, two loads make a mass of neither, with a spread so wide that no later challenger can
// contradict it (a tractor's coupled stretch, 20.9 +- 3.3 t on 500 pairs against 10.4 +- 1.0 t
// solo, left the solo belief at +104 % after the uncoupling; docs/estimator.md). But at this
// stop nothing tells whether that load is gone (the trailer uncoupled) or stays, and whether the
// belief or the drive was wrong: the drive stays in the belief, and the belief without it is
// kept until a later drive tells.
void Pipeline::hold_interlude() {
  interlude_pending_ = true;
  copy_regressor(rls_before_stop_, bayes_before_stop_, &rls_without_interlude_,
                 &bayes_without_interlude_);
  sums_without_interlude_ = sums_before_stop_;
  term_sums_without_interlude_ = term_sums_before_stop_;
  belief_without_interlude_ = belief_before_stop_;
  interlude_reading_ = load_monitor_.ended();
}

// The first later drive with pairs judges the held one. Reading the belief before it and not the
// held drive's load, the load went back: the belief returns to what it was without the held
// drive and those since (their pairs are lost; the challengers read them alone). Reading the
// held drive's load and not the belief's, the load stayed and the belief keeps them, as it
// would have. Wide enough for both, it tells nothing yet. Returns true when the belief returned.
bool Pipeline::judge_interlude() {
  const RegressorState& next = load_monitor_.ended();
  if (!load_monitor_.ended_active() || next.pairs_used == 0) return false;
  const bool reads_before = !load_monitor_.reads_apart(next, belief_without_interlude_);
  const bool reads_interlude = !load_monitor_.reads_apart(next, interlude_reading_);
  if (reads_before && reads_interlude) return false;
  interlude_pending_ = false;
  if (!reads_before) return false;
  copy_regressor(rls_without_interlude_, bayes_without_interlude_, &rls_, &bayes_);
  load_sums_ = sums_without_interlude_;
  term_sums_ = term_sums_without_interlude_;
  refit_terms();
  supervisor_.on_regressor_reset();
  has_plausible_ = false;
  return true;
}

void Pipeline::adopt_challenger() {
  end_known_mass();  // the load changed: the known mass no longer holds
  before_stop_saved_ = false;
  interlude_pending_ = false;
  // The load before the stop is the belief's evidence of the gears; the new load's pairs go on.
  if (belief_before_stop_.pairs_used > 0) {
    gear_masses_.add_evidence(sums_before_stop_, belief_before_stop_.mass_kg,
                              belief_before_stop_.mu_n);
  }
  load_sums_ = load_sums_.since(sums_before_stop_);
  sums_before_stop_ = GearPairSums{};
  term_sums_ = term_sums_.since(term_sums_before_stop_);
  term_sums_before_stop_ = PairTermSums{};
  refit_terms();
  copy_regressor(load_monitor_.challenger_rls(), load_monitor_.challenger_bayes(), &rls_, &bayes_);
  load_monitor_.dismiss();
  decide_term_fit();
  has_plausible_ = false;
  supervisor_.on_regressor_reset();
  // The belief's lag and noise pool two loads; the monitor's are (mostly) of the new load.
  longitudinal_.take_load(monitor_longitudinal_);
  longitudinal_.set_reference_mass(regressor_->state().mass_kg * pair_scale_);
  prior_ = load_monitor_.start_prior();
  prior_reason_ = StatusReason::kLoadChanged;
  estimate_.initial_mass_kg = prior_.mass_kg;
  estimate_.prior_reason = StatusReason::kLoadChanged;
}

bool Pipeline::flush() {
  if (!has_prior_ || !regressor_->flush()) return false;
  refresh_belief();
  return true;
}

void Pipeline::on_static_mass(const StaticMass& static_mass, StepResult* result) {
  // Every reported window became the static initialiser's reference (kept for snapshots).
  has_reference_ = true;
  reference_deflection_m_ = static_mass.deflection_m;
  reference_deflection_std_m_ = static_mass.deflection_std_m;
  reference_grade_accel_mps2_ = static_mass.grade_accel_mps2;
  // The first standstill after driving on the empty-mass prior does not throw away what the
  // events taught. A load change shifts the belief by the added mass (with the payload
  // prior's uncertainty) rather than forgetting what the drive taught about the vehicle.
  // A known mass holds until the load changes.
  if (known_mass_.active && !static_mass.load_changed) return;
  const RegressorState state = regressor_->state();
  const bool events_used = has_prior_ && state.pairs_used > 0;
  if (static_mass.load_changed && events_used) {
    // From the known mass, while one holds: it is the load's mass, the regression only evidence.
    const double base_kg = known_mass_.active ? known_mass_.mass_kg : state.mass_kg;
    const double base_std_kg = known_mass_.active ? known_mass_.std_kg : state.mass_std_kg;
    MassPrior shifted = static_mass.prior;
    shifted.mass_kg = base_kg + static_mass.mass_change_kg;
    shifted.mass_std_kg = std::hypot(base_std_kg, static_mass.mass_change_std_kg);
    restart(shifted, StatusReason::kLoadChanged);
  } else if (static_mass.load_changed || !events_used) {
    restart(static_mass.prior, static_mass.load_changed ? StatusReason::kLoadChanged
                                                        : StatusReason::kStaticInitialised);
  } else {
    return;
  }
  begin_static_anchor(static_mass);
  result->reinitialised = true;
  result->estimate_changed = true;
}

void Pipeline::begin_after_restore(const Sample& sample) {
  restore_pending_ = false;
  const double off_s = to_seconds(sample.time_us - restored_time_us_);
  if (off_s >= 0.0 && off_s <= params_.estimator.power_cycle_min_off_s) return;  // same drive
  // A power cycle: the load may have changed while parked, and the belief's pairs and its
  // reference deflection are of the load it had then. The mass starts afresh, as on a first
  // drive: at the first standstill window (a car that reads its load) or with the drive (one
  // that does not). The counters and what was learnt about the car carry over; the drive on a
  // known mass is evidence of the learnt scale. New tyres the drive told move the learnt scale
  // first: its known mass or standstill reading measured the scale on them.
  end_tyre_watch();
  end_known_mass();
  end_static_anchor();
  learnt_.drift();
  applied_gear_masses_ = gear_masses_;
  pair_scale_ = scale_for_pairs();
  clear_load_sums();  // the snapshot took their evidence (gear_masses_if_ended)
  has_prior_ = false;
  has_plausible_ = false;
  prior_reason_ = StatusReason::kWaitingForStandstill;
  static_init_.forget_reference();
  has_reference_ = false;
  const std::array<BlockCounters, kBlockCount> blocks = estimate_.blocks;
  estimate_ = Estimate{};
  estimate_.blocks = blocks;
  published_gear_revision_ = -1;  // the learnt gears and the tyre watch are shown again
  published_tyre_revision_ = -1;
  load_unchecked_ = true;
}

StepResult Pipeline::step(const Sample& sample) {
  StepResult result;

  if (restore_pending_) begin_after_restore(sample);
  if (declared_.active) begin_known_mass();
  watch_launches(sample);
  if (const std::optional<StaticMass> static_mass = static_init_.step(sample)) {
    on_static_mass(*static_mass, &result);
  }
  if (!has_prior_ && !params_.suspension.carries_load()) {
    restart(static_init_.no_static_prior(), StatusReason::kNoLoadSensor);
    result.reinitialised = true;
    result.estimate_changed = true;
  }
  if (!has_prior_ && sample.has(Input::kSpeed) &&
      std::abs(sample.speed_mps) > params_.estimator.static_init.standstill_speed_mps) {
    restart(static_init_.no_static_prior(), StatusReason::kNoStaticPrior);
    result.reinitialised = true;
    result.estimate_changed = true;
  }

  if (has_prior_) {
    offer_pairs(sample, &result);
    // A sensor reading the load sees every change at a standstill; without one the drive must.
    if (!params_.suspension.carries_load()) offer_monitor_pairs(sample);
    follow_beliefs();
  }
  // A challenger is adopted only with a mass vmass would publish.
  if (load_monitor_.contradicts(belief_before_stop_) &&
      plausible_mass_band(params_.vehicle).contains(load_monitor_.challenger().state().mass_kg)) {
    adopt_challenger();
    result.reinitialised = true;
    result.estimate_changed = true;
  }

  const EstimateStatus previous_status = estimate_.status;
  const StatusReason previous_reason = estimate_.reason;
  refresh_estimate(sample);
  if (estimate_.status != previous_status || estimate_.reason != previous_reason) {
    result.estimate_changed = true;
  }
  return result;
}

PipelineSnapshot Pipeline::snapshot() const {
  PipelineSnapshot s;
  s.type = params_.estimator.type;
  s.has_prior = has_prior_;
  s.prior_reason = prior_reason_;
  s.prior = prior_;
  // The open batch is saved too (closed in a copy, as published): a restart in the middle of a
  // drive would otherwise lose up to a batch of pairs. Conjugacy makes it the same belief.
  const BayesEstimator bayes = closed_bayes();
  s.pairs_used = regressor_ == &bayes_ ? bayes.state().pairs_used : rls_.state().pairs_used;
  const Eigen::Vector2d& theta = rls_.theta();
  const Eigen::Matrix2d& p = rls_.covariance();
  s.rls_theta[0] = theta(0);
  s.rls_theta[1] = theta(1);
  s.rls_covariance[0] = p(0, 0);
  s.rls_covariance[1] = p(0, 1);
  s.rls_covariance[2] = p(1, 0);
  s.rls_covariance[3] = p(1, 1);
  const NigPosterior& nig = bayes.posterior();
  s.nig_mean[0] = nig.mean(0);
  s.nig_mean[1] = nig.mean(1);
  s.nig_scaled_covariance[0] = nig.scaled_covariance(0, 0);
  s.nig_scaled_covariance[1] = nig.scaled_covariance(0, 1);
  s.nig_scaled_covariance[2] = nig.scaled_covariance(1, 0);
  s.nig_scaled_covariance[3] = nig.scaled_covariance(1, 1);
  s.nig_shape = nig.shape;
  s.nig_scale = nig.scale;
  s.has_reference = has_reference_;
  s.reference_deflection_m = reference_deflection_m_;
  s.reference_deflection_std_m = reference_deflection_std_m_;
  s.reference_grade_accel_mps2 = reference_grade_accel_mps2_;
  s.blocks[0] = supervisor_.counters(Block::kLongitudinal);
  s.blocks[1] = supervisor_.counters(Block::kLateral);
  s.time_us = estimate_.time_us;
  s.learnt = learnt_.state();
  s.static_anchor_pending = anchor_observation(&s.static_anchor);
  s.gear_masses = gear_masses_if_ended().state();
  s.known_mass = known_mass_;
  s.pair_scale = pair_scale_;
  s.pair_term_fit_applies = term_fit_applies_;
  s.pair_term_sums = term_sums_.state();
  s.tyre_watch = tyre_watch_.state();
  return s;
}

bool Pipeline::fits(const PipelineSnapshot& s) const {
  if (s.type != params_.estimator.type || !s.has_prior) {
    return false;
  }
  const MassPrior& prior = s.prior;
  if (!std::isfinite(prior.mass_kg) || !std::isfinite(prior.mu_n) ||
      !(prior.mass_std_kg > 0.0 && std::isfinite(prior.mass_std_kg)) ||
      !(prior.mu_std_n > 0.0 && std::isfinite(prior.mu_std_n)) || s.pairs_used < 0 ||
      (s.has_reference &&
       (!std::isfinite(s.reference_deflection_m) || !std::isfinite(s.reference_deflection_std_m) ||
        s.reference_deflection_std_m < 0.0)) ||
      !PairTermSums::implausible(s.pair_term_sums).empty() ||
      !TyreWatch::implausible(s.tyre_watch).empty()) {
    return false;
  }
  for (const BlockCounters& b : s.blocks) {
    if (b.ticks < 0 || b.candidates < 0 || b.accepted < 0 || b.rejected_innovation < 0) {
      return false;
    }
  }
  const AnchorObservation& a = s.static_anchor;
  if (s.static_anchor_pending &&
      (!std::isfinite(a.log_scale) || !(a.variance > 0.0) || !std::isfinite(a.variance) ||
       !(a.common_std >= 0.0) || !std::isfinite(a.common_std))) {
    return false;
  }
  if ((s.learnt_saved && !learnt_.implausible(s.learnt).empty()) ||
      (s.gear_masses_saved && !gear_masses_.implausible(s.gear_masses).empty()) ||
      !(s.pair_scale > 0.0) || !std::isfinite(s.pair_scale) ||
      (s.known_mass.active &&
       !(s.known_mass.mass_kg > 0.0 && s.known_mass.std_kg > 0.0 &&
         std::isfinite(s.known_mass.mass_kg) && std::isfinite(s.known_mass.std_kg) &&
         s.known_mass.scale_used > 0.0 && std::isfinite(s.known_mass.scale_used)))) {
    return false;
  }
  return true;
}

bool Pipeline::restore(const PipelineSnapshot& s) {
  // A car whose suspension reads the load re-checks it against the saved reference deflection
  // at its next standstill; without a reference (none was measured at this load) that
  // standstill's static prior is the start after a power cycle. A car without a load sensor
  // never has a reference; the load monitor treats the time switched off as a long stop.
  const bool carries_load = params_.suspension.carries_load();
  if (!fits(s)) return false;
  const MassPrior& prior = s.prior;
  // Try on copies first so that a refused snapshot changes nothing.
  if (s.type == RegressorType::kRls) {
    RlsEstimator trial = rls_;
    trial.reset(prior);
    Eigen::Matrix2d p;
    p << s.rls_covariance[0], s.rls_covariance[1], s.rls_covariance[2], s.rls_covariance[3];
    if (!trial.restore(Eigen::Vector2d(s.rls_theta[0], s.rls_theta[1]), p, s.pairs_used)) {
      return false;
    }
    rls_ = trial;
  } else {
    NigPosterior nig;
    nig.mean << s.nig_mean[0], s.nig_mean[1];
    nig.scaled_covariance << s.nig_scaled_covariance[0], s.nig_scaled_covariance[1],
        s.nig_scaled_covariance[2], s.nig_scaled_covariance[3];
    nig.shape = s.nig_shape;
    nig.scale = s.nig_scale;
    BayesEstimator trial = bayes_;
    trial.reset(prior);
    if (!trial.restore(nig, s.pairs_used)) return false;
    bayes_ = trial;
  }
  if (s.learnt_saved) learnt_.restore(s.learnt);
  if (s.static_anchor_pending) {
    static_anchor_.hold(s.static_anchor);
  } else {
    static_anchor_.end();
  }
  if (s.gear_masses_saved) gear_masses_.restore(s.gear_masses);
  tyre_watch_.restore(s.tyre_watch);
  applied_gear_masses_ = gear_masses_;
  load_sums_ = GearPairSums{};  // the snapshot's gear masses hold their evidence
  sums_before_stop_ = GearPairSums{};
  // The belief restored holds the load's pairs: so do its terms' sums.
  term_sums_ = PairTermSums::restored(s.pair_term_sums);
  term_sums_before_stop_ = PairTermSums{};
  term_fit_applies_ = s.pair_term_fit_applies;
  refit_terms();
  known_mass_ = s.known_mass;
  pair_scale_ = s.pair_scale;
  supervisor_.on_regressor_reset();
  supervisor_.restore_counters(Block::kLongitudinal, s.blocks[0]);
  supervisor_.restore_counters(Block::kLateral, s.blocks[1]);
  reset_extractors(prior.mass_kg);
  if (s.has_reference) {
    static_init_.restore_reference(s.reference_deflection_m, s.reference_deflection_std_m,
                                   s.reference_grade_accel_mps2);
  }
  if (!carries_load) load_monitor_.assume_long_stop();
  before_stop_saved_ = false;  // the belief before the last stop was not saved
  interlude_pending_ = false;
  has_reference_ = s.has_reference;
  reference_deflection_m_ = s.reference_deflection_m;
  reference_deflection_std_m_ = s.reference_deflection_std_m;
  reference_grade_accel_mps2_ = s.reference_grade_accel_mps2;
  has_prior_ = true;
  prior_reason_ = StatusReason::kRestored;
  prior_ = prior;
  restore_pending_ = true;
  restored_time_us_ = s.time_us;
  load_unchecked_ = false;

  const RegressorState state = with_term_shift(regressor_->state());
  has_plausible_ = false;
  publish_state(state);
  estimate_.initial_mass_kg = prior.mass_kg;
  estimate_.prior_reason = StatusReason::kRestored;
  estimate_.blocks = s.blocks;
  estimate_.status =
      state.pairs_used > 0 ? EstimateStatus::kConverging : EstimateStatus::kStaticOnly;
  estimate_.reason = StatusReason::kRestored;
  return true;
}

bool Pipeline::declare_known_mass(double mass_kg, double std_kg) {
  const MassBand band = plausible_mass_band(params_.vehicle);
  if (!std::isfinite(mass_kg) || !band.contains(mass_kg) || !(std_kg > 0.0) ||
      !std::isfinite(std_kg)) {
    return false;
  }
  declared_ = KnownMass{true, mass_kg, std_kg, 1.0};
  return true;
}

void Pipeline::begin_known_mass() {
  // The regression restarts from the known mass with a vague prior: the drive's pairs, not the
  // declaration, are the evidence of the scale (scale_observation()).
  MassPrior prior = static_init_.no_static_prior();
  prior.mass_kg = declared_.mass_kg;
  prior.mass_std_kg = params_.estimator.learning.anchor_prior_std_fraction * declared_.mass_kg;
  restart(prior, StatusReason::kKnownMass);
  known_mass_ = declared_;
  known_mass_.scale_used = pair_scale_;
  declared_.active = false;
  has_plausible_ = true;
}

void Pipeline::end_known_mass() {
  if (!known_mass_.active) return;
  ScaleObservation seen;
  if (scale_observation(known_mass_, belief_state(), params_.estimator.learning, &seen)) {
    // The scale now holds this drive's gear mix at the corrections it had, as much as it
    // takes the evidence (less for an outlier).
    gear_masses_.add_reference(load_sums_, known_mass_.mass_kg,
                               learnt_.taken_variance(seen.log_scale, seen.variance),
                               declared_scale_variance(params_.vehicle), applied_gear_masses_);
    learnt_.add_evidence(seen.log_scale, seen.variance);
  }
  known_mass_.active = false;
}

void Pipeline::begin_static_anchor(const StaticMass& static_mass) {
  // Its own regression starts as a known mass's does: vague, at the reading.
  MassPrior vague = static_init_.no_static_prior();
  vague.mass_std_kg =
      params_.estimator.learning.anchor_prior_std_fraction * static_mass.prior.mass_kg;
  static_anchor_.begin(static_mass.prior, static_init_.base_std_kg(), pair_scale_, vague);
}

bool Pipeline::anchor_observation(AnchorObservation* out) const {
  return static_anchor_.observation(params_.estimator.learning, out);
}

void Pipeline::end_static_anchor() {
  AnchorObservation seen;
  if (anchor_observation(&seen)) learnt_.add_anchor(seen.log_scale, seen.variance, seen.common_std);
  static_anchor_.end();
}

LearntScale Pipeline::learnt_with_anchor() const {
  LearntScale out = learnt_;
  AnchorObservation seen;
  if (anchor_observation(&seen)) out.add_anchor(seen.log_scale, seen.variance, seen.common_std);
  return out;
}

LearntScale Pipeline::learnt_scale_if_ended() const {
  LearntScale out = learnt_with_anchor();
  ScaleObservation seen;
  if (scale_observation(known_mass_, belief_state(), params_.estimator.learning, &seen)) {
    out.add_evidence(seen.log_scale, seen.variance);
  }
  return out;
}

void Pipeline::reset_learnt() {
  learnt_.reset();
  gear_masses_.reset();
  tyre_watch_.reset();
  applied_gear_masses_ = gear_masses_;
}

void Pipeline::tyres_changed() {
  // What this load taught so far was read on the old tyres: its known mass's and its standstill
  // reading's evidence are taken as such, before the widening (which drops the anchors). The
  // known mass ends there: after a power cycle it may no longer be the load's (a weighbridge
  // after the workshop is declared after this command).
  end_known_mass();
  end_static_anchor();
  learnt_.tyres_changed();
  tyre_watch_.tyres_declared();
  // The scale's mean is kept, so the pairs' scale stands; the interval widens from the next tick.
}

bool Pipeline::restore_learnt(const PipelineSnapshot& s) {
  if (s.gear_masses_saved && !gear_masses_.implausible(s.gear_masses).empty()) return false;
  if (!learnt_.restore(s.learnt)) return false;
  if (s.gear_masses_saved) gear_masses_.restore(s.gear_masses);
  applied_gear_masses_ = gear_masses_;
  // A restart with its load unknown is a power cycle: the saved drive ends.
  if (tyre_watch_.restore(s.tyre_watch)) end_tyre_watch();
  learnt_.drift();
  if (!has_prior_) pair_scale_ = scale_for_pairs();
  return true;
}

void Pipeline::publish_known_mass() {
  // What the user declared is the load's mass until it changes; the regression goes on as the
  // scale's evidence and the load-change check.
  estimate_.mass_kg = known_mass_.mass_kg;
  estimate_.mass_std_kg = known_mass_.std_kg;
  estimate_.mass_model_std_kg = 0.0;
  estimate_.ci_low_kg = known_mass_.mass_kg - kNormal95 * known_mass_.std_kg;
  estimate_.ci_high_kg = known_mass_.mass_kg + kNormal95 * known_mass_.std_kg;
  estimate_.mass_known = true;
  estimate_.plausible = true;
  if (estimate_.invalid_inputs != 0) return;  // degraded stays degraded
  // Without a load sensor, a long stop may have changed the load unseen: converged again once
  // the load monitor's challenger has had its pairs (as for any belief).
  estimate_.status = load_monitor_.undecided() || !published_narrow() ? EstimateStatus::kConverging
                                                                      : EstimateStatus::kConverged;
  estimate_.reason = StatusReason::kKnownMass;
}

bool Pipeline::published_narrow() const {
  const double half_width = 0.5 * (estimate_.ci_high_kg - estimate_.ci_low_kg);
  return half_width <= params_.estimator.converged_halfwidth_fraction * std::abs(estimate_.mass_kg);
}

void Pipeline::refresh_estimate(const Sample& sample) {
  estimate_.time_us = sample.time_us;
  estimate_.blocks[0] = supervisor_.counters(Block::kLongitudinal);
  estimate_.blocks[1] = supervisor_.counters(Block::kLateral);

  InputMask needed = input_bit(Input::kSpeed);
  if (params_.suspension.carries_load()) needed |= input_bit(Input::kRearRightDeflection);
  if (params_.estimator.longitudinal.enabled) needed |= longitudinal_.required_inputs();
  if (params_.estimator.lateral.enabled) needed |= LateralExtractor::kRequired;
  estimate_.invalid_inputs = needed & ~sample.valid;
  // As the next drive will divide by it (what is learnt so far).
  estimate_.learnt_scale = learnt_.scale() * gear_masses_.scale_factor();
  estimate_.learnt_scale_std = learnt_.relative_std();
  estimate_.learnt_evidence = learnt_.state().evidence;
  estimate_.learnt_changes = learnt_.state().changes;
  estimate_.learnt_anchors = learnt_.state().anchors;
  estimate_.learnt_tyre_changes = learnt_.state().tyre_changes;
  estimate_.learnt_evidence_since_tyres = learnt_.state().evidence_since_tyres;
  estimate_.known_mass = known_mass_.active;
  publish_learnt_gears();
  publish_tyre_watch();
  publish_pair_term_fit();
  refresh_belief();
}

void Pipeline::refresh_belief() {
  if (!has_prior_) {
    estimate_.status = EstimateStatus::kInitialising;
    estimate_.reason =
        load_unchecked_ ? StatusReason::kLoadUnchecked : StatusReason::kWaitingForStandstill;
    if (estimate_.invalid_inputs != 0) {
      estimate_.status = EstimateStatus::kDegraded;
      estimate_.reason = StatusReason::kInputsInvalid;
    }
    return;
  }
  RegressorState state = belief_state();
  const bool provisional = provisional_state(&state);
  publish_state(with_term_shift(state));
  const LagEstimator& lag = longitudinal_.lag();
  estimate_.driveline_lag_s = lag.identified() ? lag.lag_s() : -1.0;
  if (state.pairs_used > 0) {
    estimate_.force_noise_std_n = longitudinal_.force_noise_n();
    estimate_.accel_noise_std_mps2 = longitudinal_.accel_noise_mps2();
  }

  if (estimate_.invalid_inputs != 0) {
    estimate_.status = EstimateStatus::kDegraded;
    estimate_.reason = StatusReason::kInputsInvalid;
  } else if (!estimate_.mass_known) {
    estimate_.status = EstimateStatus::kDegraded;
    estimate_.reason = StatusReason::kMassImplausible;
  } else if (provisional) {
    estimate_.status = EstimateStatus::kConverging;
    estimate_.reason = StatusReason::kLagProvisional;
  } else if (state.pairs_used == 0) {
    // Only a suspension that reads the load gives a static mass (a restored belief of a car
    // without one is a prior, not a reading).
    const bool static_prior =
        params_.suspension.carries_load() && prior_reason_ != StatusReason::kNoStaticPrior;
    estimate_.status = static_prior ? EstimateStatus::kStaticOnly : EstimateStatus::kInitialising;
    estimate_.reason = prior_reason_;
  } else if (estimate_.plausible && load_monitor_.suspects(belief_before_stop_)) {
    span_challenger();
    estimate_.status = EstimateStatus::kConverging;
    estimate_.reason = StatusReason::kLoadChangeSuspected;
  } else {
    // Converged: more driving would not narrow it (the regression's part is small), no stop
    // since may have changed the load unseen (without a load sensor, the load monitor's
    // challenger has had the pairs it needs to tell), and the interval published is narrow.
    const double regression_half_width = 0.5 * (state.ci_high_kg - state.ci_low_kg);
    const bool settled = regression_half_width < params_.estimator.converged_ci_halfwidth_fraction *
                                                     std::abs(state.mass_kg) &&
                         !load_monitor_.undecided();
    const bool narrow = settled && published_narrow();
    estimate_.status = narrow ? EstimateStatus::kConverged : EstimateStatus::kConverging;
    if (narrow) {
      estimate_.reason = StatusReason::kIntervalNarrow;
    } else {
      // Settled inside a wide interval: only what the config leaves unknown keeps it wide.
      estimate_.reason = settled ? StatusReason::kModelLimited : StatusReason::kRefining;
    }
  }
  // A known mass holds for its load: while the drive since a stop says the load changed, the
  // published estimate is the suspicion's (the challenger's, spanning both), not the declaration.
  if (known_mass_.active && estimate_.reason != StatusReason::kLoadChangeSuspected) {
    publish_known_mass();
  }
}

namespace {

// A copy of the belief updated with the held pairs at lag_s; false when none passes the gates.
template <class Regressor>
bool with_held_pairs(Regressor scratch, const LongitudinalExtractor& block, double lag_s,
                     double information, double pair_scale, RegressorState* out) {
  bool any = false;
  for (std::size_t i = 0; i < block.pending_count(); ++i) {
    Extraction held = block.provisional(i, lag_s);
    if (!held.has_pair()) continue;
    divide_force(&held.pair, pair_scale);
    held.pair.information = information;
    scratch.update(held.pair);
    any = true;
  }
  if (!any) return false;
  scratch.flush();
  *out = scratch.state();
  return true;
}

}  // namespace

RegressorState Pipeline::belief_state() const {
  if (regressor_ != &bayes_ || bayes_.pending_pairs() == 0) return regressor_->state();
  return closed_bayes().state();
}

BayesEstimator Pipeline::closed_bayes() const {
  BayesEstimator closed = bayes_;
  if (closed.pending_pairs() > 0) closed.flush();
  return closed;
}

bool Pipeline::provisional_state(RegressorState* out) const {
  const LagEstimator& lag = longitudinal_.lag();
  const double spread_s = params_.estimator.longitudinal.lag.provisional_std_s;
  if (lag.identified() || longitudinal_.pending_count() == 0 || !(spread_s > 0.0)) return false;
  const double max_lag_s = params_.estimator.longitudinal.lag.max_lag_s;
  const double best_s = lag.best_lag_s();
  // The mass at the best fit and a lag's std either way (clamped to the candidate range).
  RegressorState at[3];
  const double lags[3] = {best_s, std::max(best_s - spread_s, 0.0),
                          std::min(best_s + spread_s, max_lag_s)};
  for (int k = 0; k < 3; ++k) {
    const bool ok =
        params_.estimator.type == RegressorType::kBayes
            ? with_held_pairs(bayes_, longitudinal_, lags[k], pair_information_, pair_scale_,
                              &at[k])
            : with_held_pairs(rls_, longitudinal_, lags[k], pair_information_, pair_scale_, &at[k]);
    if (!ok) return false;
  }
  // The lag's uncertainty adds to the regression's in quadrature, at the interval's quantile.
  RegressorState state = at[0];
  const double lag_std_kg = 0.5 * std::abs(at[2].mass_kg - at[1].mass_kg);
  const double half_width = 0.5 * (state.ci_high_kg - state.ci_low_kg);
  const double z = state.mass_std_kg > 0.0 ? half_width / state.mass_std_kg : kNormal95;
  const double widened = std::hypot(half_width, z * lag_std_kg);
  state.mass_std_kg = std::hypot(state.mass_std_kg, lag_std_kg);
  state.ci_low_kg = state.mass_kg - widened;
  state.ci_high_kg = state.mass_kg + widened;
  *out = state;
  return true;
}

double Pipeline::model_std_kg(double mass_kg) const {
  // The lumped scale's std: learnt from the car's known masses, or the datasheet's (widened by
  // new tyres once declared).
  const VehicleParams& v = params_.vehicle;
  // A step of the launches suspected but not yet a change: the scale may have moved by it.
  const double scale_variance =
      (learnt_.replaces_datasheet() ? learnt_.log_scale_var() : declared_scale_variance(v)) +
      tyre_watch_.suspected_variance();
  // A kappa measured on this car holds the car's own share of the model error: what is left of
  // the floor is the drive's.
  const double floor = learnt_.learnt() ? params_.estimator.learning.drive_error_std_fraction
                                        : params_.estimator.model_error_std_fraction;
  return model_std_kg(mass_kg, scale_variance, floor);
}

double Pipeline::unshared_model_std_kg(double mass_kg) const {
  return model_std_kg(mass_kg, 0.0, params_.estimator.model_error_std_fraction);
}

double Pipeline::model_std_kg(double mass_kg, double scale_variance, double floor) const {
  const double relative = std::sqrt(scale_variance + floor * floor);
  // The rotating masses' and the converter map's errors move the mass by their share of it, in
  // kg (a truck's low gears, an automatic pulling away).
  if (fits_pair_terms()) {
    return std::hypot(relative * std::abs(mass_kg), term_fit_.mass_std_kg);
  }
  const double rotating_kg = rotating_std_kg(mass_kg);
  const double converter_kg = kUniformStdPerBound *
                              params_.vehicle.torque_converter_map_accuracy_fraction *
                              converter_sensitivity_.sensitivity_kg();
  return std::hypot(relative * std::abs(mass_kg), rotating_kg, converter_kg);
}

void Pipeline::decide_term_fit() {
  // What the car has learnt (its gears' masses, the lumped scale a known mass gave) already
  // holds the terms' errors, as they were on the drives it learnt from.
  term_fit_applies_ =
      params_.estimator.fit_pair_terms && !applied_gear_masses_.learnt() && !learnt_.learnt();
  refit_terms();
}

std::optional<PairTermFit> Pipeline::pair_term_fit() const {
  if (!fits_pair_terms()) return std::nullopt;
  return term_fit_;
}

bool Pipeline::fits_pair_terms() const { return term_fit_applies_ && term_sums_.pairs() >= 2; }

void Pipeline::refit_terms() {
  if (!fits_pair_terms()) {
    term_fit_ = PairTermFit{};
    return;
  }
  const VehicleParams& v = params_.vehicle;
  term_fit_ = term_sums_.fit({kUniformStdPerBound * v.rotating_mass_accuracy_fraction,
                              kUniformStdPerBound * v.torque_converter_map_accuracy_fraction});
}

RegressorState Pipeline::with_term_shift(RegressorState state) const {
  if (state.pairs_used == 0) return state;
  const double shift_kg = term_fit_.mass_shift_kg;
  state.mass_kg += shift_kg;
  state.ci_low_kg += shift_kg;
  state.ci_high_kg += shift_kg;
  return state;
}

double Pipeline::rotating_std_kg(double mass_kg) const {
  const double datasheet_std =
      kUniformStdPerBound * params_.vehicle.rotating_mass_accuracy_fraction;
  if (!applied_gear_masses_.learnt()) {
    return datasheet_std * rotating_sensitivity_.sensitivity_kg();
  }
  // The learnt gears' belief, and the datasheet's error of the pairs outside them (no gear, an
  // unlocked converter).
  const double unlearnt_kg =
      interval_sums_.all_da_da > 0.0
          ? datasheet_std * interval_sums_.unlearnt_da_term / interval_sums_.all_da_da
          : 0.0;
  return std::sqrt(applied_gear_masses_.mass_variance_kg2(interval_sums_, mass_kg) +
                   unlearnt_kg * unlearnt_kg);
}

double Pipeline::published_half_width(const RegressorState& state) const {
  // The regression's own 95 % quantile (Student t or normal); the normal one without a spread.
  const double z = state.mass_std_kg > 0.0
                       ? 0.5 * (state.ci_high_kg - state.ci_low_kg) / state.mass_std_kg
                       : kNormal95;
  return std::hypot(0.5 * (state.ci_high_kg - state.ci_low_kg), z * model_std_kg(state.mass_kg));
}

// A suspected load change (LoadChangeMonitor::suspects): the published interval spans the main
// belief's and the challenger's, each with the model error, so that it holds whichever is right
// until the monitor decides. While the challenger is undecided the estimate is its own: its 95 %
// interval already excludes the belief, so the drive since the stop is the better evidence of
// today's load. Once it has had its pairs and still neither decides nor agrees, the estimate is
// the two weighted by the probability that the load changed: a part of a drive, in fewer gears
// than the whole, reads further from it than its statistics say, and on a truck most such
// suspicions at a drive's end were of no change (docs/estimator.md).
void Pipeline::span_challenger() {
  const RegressorState c = load_monitor_.challenger().state();
  if (c.mass_kg >= estimate_.plausible_low_kg && c.mass_kg <= estimate_.plausible_high_kg) {
    const double p = load_monitor_.undecided() ? 1.0 : probability_load_changed(c);
    estimate_.mass_kg = p * c.mass_kg + (1.0 - p) * estimate_.mass_kg;
    estimate_.mu_n = p * c.mu_n + (1.0 - p) * estimate_.mu_n;
  }
  const double half_width = published_half_width(c);
  estimate_.ci_low_kg = std::min(estimate_.ci_low_kg, c.mass_kg - half_width);
  estimate_.ci_high_kg = std::max(estimate_.ci_high_kg, c.mass_kg + half_width);
  estimate_.mass_std_kg = std::max(estimate_.mass_std_kg,
                                   0.5 * (estimate_.ci_high_kg - estimate_.ci_low_kg) / kNormal95);
}

// The challenger against the belief before the stop, each with the model error it does not
// share with the other (both are read through the same lumped scale).
double Pipeline::probability_load_changed(const RegressorState& challenger) const {
  const RegressorState& before = belief_before_stop_;
  const double std_kg = std::sqrt(challenger.mass_std_kg * challenger.mass_std_kg +
                                  before.mass_std_kg * before.mass_std_kg +
                                  std::pow(unshared_model_std_kg(challenger.mass_kg), 2) +
                                  std::pow(unshared_model_std_kg(before.mass_kg), 2));
  // A changed load is anywhere between empty and full; without a maximum, in the plausible band.
  const double capacity_kg = params_.vehicle.payload_capacity_kg();
  const double span_kg =
      capacity_kg > 0.0 ? capacity_kg : estimate_.plausible_high_kg - estimate_.plausible_low_kg;
  return load_change_probability(challenger.mass_kg - before.mass_kg, std_kg, span_kg,
                                 params_.estimator.load_change.change_prior);
}

void Pipeline::publish_state(const RegressorState& state) {
  const MassBand band = plausible_mass_band(params_.vehicle);
  estimate_.plausible_low_kg = band.low_kg;
  estimate_.plausible_high_kg = band.high_kg;
  estimate_.pairs_used = state.pairs_used;
  const bool plausible = band.contains(state.mass_kg);
  estimate_.plausible = plausible;
  estimate_.implausible_mass_kg = plausible ? 0.0 : state.mass_kg;
  if (!plausible && has_plausible_) return;  // hold the last plausible estimate
  // Never a plausible estimate of this load: no mass at all rather than one vmass would refuse
  // to restore (refresh_belief() says why).
  estimate_.mass_known = plausible;
  if (!plausible) return;
  has_plausible_ = true;
  const double model_std = model_std_kg(state.mass_kg);
  const double half_width = published_half_width(state);
  estimate_.mass_kg = state.mass_kg;
  estimate_.mu_n = state.mu_n;
  estimate_.mass_model_std_kg = model_std;
  estimate_.mass_std_kg = std::hypot(state.mass_std_kg, model_std);
  estimate_.ci_low_kg = state.mass_kg - half_width;
  estimate_.ci_high_kg = state.mass_kg + half_width;
}

}  // namespace vmass

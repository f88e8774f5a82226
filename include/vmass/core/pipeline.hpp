// Pipeline: the whole estimator of the paper (Fig. 3) on a stream of Samples.
//
//   Sample -> StaticInitializer (eq. 3, load changes)    -> prior of the regressor
//          (no sensor reading the load: the no-static prior, and LoadChangeMonitor with its
//           own extractors)
//          -> LongitudinalExtractor (eqs. 4-7, Table II)  -> Supervisor (eq. 13, innovation
//          -> LateralExtractor (eqs. 8-12, Table III)     -> gate) -> RlsEstimator | BayesEstimator
//          -> Estimate
//
// step() is called once per tick with the sample of that tick (time stamps increasing); it
// returns whether the published estimate changed and the per-block diagnostic records. Same
// sample sequence -> bit-identical estimates, in the daemon and offline.
//
// snapshot() / restore() carry the estimate across a restart of the daemon (persistence): the
// regressor's belief (RLS theta and P, or the NIG posterior), the prior that started it, the
// reference standstill deflection, the block counters and the time the snapshot was taken.
// The open Bayes batch is saved closed into the posterior (as the estimate publishes it); the
// extractors' short histories and the pairs held until the lag is identified are not carried over.
//
// The first step after restore() tells a restart within a drive from the vehicle's next drive:
//   - within a drive (its sample at most estimator.power_cycle_min_off_s after the snapshot):
//     the belief goes on as it was; a stop meanwhile is re-checked as any stop is (the next
//     standstill window against the reference; without a load sensor, the load monitor counts
//     the time off as a long stop);
//   - a power cycle (longer, or a clock that went back): the load may have changed while parked,
//     and the pairs of yesterday's load are no evidence of today's, nor its reference deflection
//     of today's load. The mass starts afresh, exactly as on a first drive (reason
//     load_unchecked until the first standstill window or the drive gives it a prior); only the
//     block counters carry over. What does carry over from drive to drive is what the load does
//     not change: the vehicle's constants.
// So a belief never grows more confident from drive to drive than one drive makes it.
//
// Pure: no threads, clocks, files or logging. Not thread-safe. Allocates only in the
// constructor.
#pragma once

#include <array>
#include <limits>
#include <optional>
#include <string>

#include "vmass/core/bayes_estimator.hpp"
#include "vmass/core/estimate.hpp"
#include "vmass/core/extraction.hpp"
#include "vmass/core/known_mass.hpp"
#include "vmass/core/lateral_extractor.hpp"
#include "vmass/core/launch_integrator.hpp"
#include "vmass/core/learnt_gear_masses.hpp"
#include "vmass/core/learnt_scale.hpp"
#include "vmass/core/load_change_monitor.hpp"
#include "vmass/core/longitudinal_extractor.hpp"
#include "vmass/core/pair_term_fit.hpp"
#include "vmass/core/pair_term_sensitivity.hpp"
#include "vmass/core/rls_estimator.hpp"
#include "vmass/core/static_anchor.hpp"
#include "vmass/core/static_initializer.hpp"
#include "vmass/core/supervisor.hpp"
#include "vmass/core/vehicle_params.hpp"

namespace vmass {

enum class RegressorType : std::uint8_t { kRls, kBayes };
std::string_view regressor_type_name(RegressorType t);

struct EstimatorParams {
  RegressorType type = RegressorType::kBayes;
  DifferencingParams differencing;
  StaticInitParams static_init;
  LoadChangeParams load_change;
  LongitudinalParams longitudinal;
  LateralParams lateral;
  SupervisorParams supervisor;
  RlsParams rls;
  BayesParams bayes;
  LearningParams learning;
  /// The regression has converged (more driving would not narrow it) when its own 95 %
  /// half-width is below this fraction of the mass.
  double converged_ci_halfwidth_fraction = 0.01;
  /// `converged` also needs the published 95 % half-width (the regression's and the model
  /// error's: what the config leaves unknown about the car) below this fraction of the mass;
  /// above it the status is `converging (model_limited)`. 5 %: the paper's "within 1 to 5 %
  /// of the real mass", the widest interval a mass estimate is asked to be useful at.
  double converged_halfwidth_fraction = 0.05;
  /// Ticks over which consecutive pairs share their noise; each pair counts as 1/this of an
  /// independent observation (RegressionPair::information). 0 = automatic: the low-pass's
  /// time constant, tick_rate / (2 pi cutoff), or 1 without the filter. Measured on the
  /// simulator: with 1 the Bayes interval covered the truth on 37-46 % of the ticks of
  /// paper_exp1 (seeds 2, 3); with the automatic 3.2, on 100 %.
  double pair_correlation_ticks = 0.0;
  /// Relative std of the mass that the model's unmodelled effects leave and no driving averages
  /// away (the driveline mode's residue after the low-pass, datasheet errors of the aero,
  /// rolling and rotating terms, wheel-speed errors): a floor of the published interval,
  /// in quadrature with the declared accuracies (Estimate::mass_model_std_kg).
  double model_error_std_fraction = 0.01;
  /// Until the gears' rotating masses are learnt, fit the errors of the configured rotating
  /// masses and converter map from the load's own pairs (PairTermSums) and take them off the
  /// mass; the interval keeps what the pairs leave unknown of them.
  bool fit_pair_terms = true;
  /// A restore whose first input comes more than this after the snapshot (or before it: a
  /// clock that went back) is a power cycle: the vehicle was off, the load may have changed,
  /// and the mass starts afresh. Within it the daemon restarted during a drive (a crash, the
  /// watchdog: the state is at most daemon.persist_interval_s old, plus systemd's RestartSec)
  /// and the belief goes on; a stop meanwhile is re-checked as any stop is.
  double power_cycle_min_off_s = 120.0;

  /// The correlation ticks in effect for pairs differenced with `d` (>= 1).
  double effective_pair_correlation_ticks(const DifferencingParams& d) const;
  /// The load-change challenger's differencing (LoadChangeParams) at the estimator's tick rate.
  DifferencingParams monitor_differencing() const;
  std::string validate() const;
};

struct PipelineParams {
  VehicleParams vehicle;
  SuspensionParams suspension;
  EstimatorParams estimator;

  std::string validate() const;
};

struct StepResult {
  bool estimate_changed = false;
  bool reinitialised = false;  ///< a (new) static prior restarted the regressor this tick
  std::array<PairEvent, kBlockCount> events{};
};

/// The state persistence needs to resume a Pipeline (plain values: trivially copyable, so it can
/// be handed between threads without allocation).
struct PipelineSnapshot {
  RegressorType type = RegressorType::kBayes;
  bool has_prior = false;  ///< false: nothing worth saving (restore() refuses it)
  StatusReason prior_reason = StatusReason::kWaitingForStandstill;
  MassPrior prior;  ///< the prior that (re)started the regressor (sets the RLS bound)
  long pairs_used = 0;
  // RLS (type kRls): theta = [M, mu] and its covariance P, row-major.
  double rls_theta[2] = {0.0, 0.0};
  double rls_covariance[4] = {0.0, 0.0, 0.0, 0.0};
  // Bayes (type kBayes): the NIG posterior (m, V row-major, a, b).
  double nig_mean[2] = {0.0, 0.0};
  double nig_scaled_covariance[4] = {0.0, 0.0, 0.0, 0.0};
  double nig_shape = 0.0;
  double nig_scale = 0.0;
  // The standstill window the current load was measured in (eq. 3), for load-change detection.
  bool has_reference = false;
  double reference_deflection_m = 0.0;
  double reference_deflection_std_m = 0.0;
  double reference_grade_accel_mps2 = std::numeric_limits<double>::quiet_NaN();  ///< NaN: unknown
  std::array<BlockCounters, kBlockCount> blocks{};
  TimeUs time_us = 0;  ///< the time of the last step before it was taken
  // What is learnt about the car across drives, and the known mass of the current load.
  bool learnt_saved = true;  ///< false: a state from before them (restore keeps the pipeline's)
  LearntScaleState learnt;
  /// false: a state from before the gears were learnt (restore keeps the pipeline's). Saved as
  /// if the drive ended at the snapshot (its gears' evidence taken).
  bool gear_masses_saved = true;
  GearMassesState gear_masses;
  KnownMass known_mass;
  /// The current load's static anchor's evidence so far (taken at the next power cycle).
  bool static_anchor_pending = false;
  AnchorObservation static_anchor;
  double pair_scale = 1.0;  ///< the scale the current belief's pairs were divided by
  /// The launches' and stops' log s, across drives and this drive's (TyreWatch; format 8, older
  /// states: nothing watched yet).
  TyreWatchState tyre_watch;
  /// The current load's pair-term fit: whether it applies, and its sums (format 7; older
  /// states: it does not apply).
  bool pair_term_fit_applies = false;
  PairTermSumsState pair_term_sums;
};

class Pipeline {
 public:
  /// params must be valid (validate() == "").
  explicit Pipeline(const PipelineParams& params);
  Pipeline(const Pipeline&) = delete;  // holds a pointer to its own active regressor
  Pipeline& operator=(const Pipeline&) = delete;

  StepResult step(const Sample& sample);
  /// Takes the accepted pairs the regressor still holds back (the open Bayes batch) into the
  /// estimate: call it after the last step of a log and before the daemon's final state save.
  /// The estimate keeps the last step's time and inputs; returns whether it changed.
  bool flush();
  const Estimate& estimate() const { return estimate_; }
  const MassRegressor& regressor() const { return *regressor_; }
  /// The longitudinal block (its identified lag and measured noise, for the status).
  const LongitudinalExtractor& longitudinal() const { return longitudinal_; }
  const PipelineParams& params() const { return params_; }
  /// Student-t quantiles evaluated so far (the belief's and the load monitor's; a work counter
  /// that tests bound per tick: the evaluation is the costliest call a tick can make).
  std::int64_t quantile_evaluations() const {
    return bayes_.quantiles().evaluations() +
           load_monitor_.challenger_bayes().quantiles().evaluations();
  }

  /// The current state, for persistence. Allocates nothing.
  PipelineSnapshot snapshot() const;
  /// Resume from a snapshot of a pipeline with the same parameters. Returns false and changes
  /// nothing when it does not fit: another regressor type, no prior, a non-finite value, or a
  /// belief the regressor refuses
  /// (see RlsEstimator::restore, BayesEstimator::restore). On success the estimate reads
  /// reason `restored` until the next step, which decides between a restart within a drive and
  /// a power cycle (see the header).
  bool restore(const PipelineSnapshot& snapshot);

  /// The user declares the current load's mass (a weighbridge ticket, "empty, driver only"):
  /// from the next step the pipeline publishes it and learns the lumped scale from the drive on
  /// it (KnownMass). std_kg > 0; mass_kg inside the plausible band (else false, nothing
  /// changed).
  bool declare_known_mass(double mass_kg, double std_kg);
  /// Forget what was learnt about the car (back to the config's datasheet values).
  void reset_learnt();
  /// New tyres were fitted (a workshop's declaration): the current load's evidence so far (read
  /// on the old tyres) is taken and its known mass ends, then the learnt scale widens by the
  /// radius's uncertainty and its static anchors start again (LearntScale::tyres_changed); the
  /// rotating masses are kept.
  void tyres_changed();
  /// Resume what was learnt about the car alone (the snapshot's learnt scale and gear masses,
  /// when its mass section does not fit); false and nothing changed when either is refused.
  bool restore_learnt(const PipelineSnapshot& snapshot);
  const LearntScale& learnt_scale() const { return learnt_; }
  const LearntGearMasses& gear_masses() const { return gear_masses_; }
  const TyreWatch& tyre_watch() const { return tyre_watch_; }
  /// What the learnt gear masses would be if the drive ended now (its gears' evidence taken).
  LearntGearMasses gear_masses_if_ended() const;
  /// What the learnt scale would be if the drive ended now (the known mass's or the static
  /// anchor's evidence taken).
  LearntScale learnt_scale_if_ended() const;
  /// The current load's pair-term fit (the rotating masses' and the converter map's errors, the
  /// shift of the mass), when it applies and has pairs enough; empty otherwise.
  std::optional<PairTermFit> pair_term_fit() const;

 private:
  /// The snapshot is one restore() could take: its type, finite values, counts, learnt section.
  bool fits(const PipelineSnapshot& snapshot) const;
  void restart(const MassPrior& prior, StatusReason reason);
  /// The known mass's evidence into the learnt scale (if it has any), and the known mass ends.
  void end_known_mass();
  /// The load's standstill reading anchors the learnt scale from now (StaticAnchor).
  void begin_static_anchor(const StaticMass& static_mass);
  /// The static anchor's evidence into the learnt scale (if it has any), and the anchor ends.
  void end_static_anchor();
  /// The learnt scale with the static anchor's evidence so far taken.
  LearntScale learnt_with_anchor() const;
  /// The static anchor's evidence so far; false when it has none.
  bool anchor_observation(AnchorObservation* out) const;
  /// A launch from a standstill or a stop to one that ends on this tick tells the tyres
  /// (TyreWatch).
  void watch_launches(const Sample& sample);
  /// The drive ended: new tyres it told move the learnt scale (LearntScale::tyres_measured).
  void end_tyre_watch();
  /// The current load's gears' evidence into the learnt gear masses; the load's sums restart.
  void end_gear_evidence();
  /// What is learnt about each gear's rotating mass, into the estimate.
  void publish_learnt_gears();
  /// What the tyre watch holds and the drive's pair-term fit, into the estimate.
  void publish_tyre_watch();
  void publish_pair_term_fit();
  /// The scale the pairs' force is divided by: the learnt one, less the gear-mix level its
  /// known-mass evidence holds that the applied gear corrections take off in kg.
  double scale_for_pairs() const;
  /// A longitudinal pair in the belief's units: divided by the learnt scale, its gear's learnt
  /// rotating-mass correction subtracted.
  void to_belief_units(RegressionPair* pair) const;
  /// The pair's force before the learnt correction of its gear (in the belief's units).
  double uncorrected_y_n(const RegressionPair& pair) const;
  /// The rotating masses' std in the mass, kg: the learnt belief's once it rests on a drive,
  /// else the datasheet's.
  double rotating_std_kg(double mass_kg) const;
  /// Whether the modelled terms' errors are fitted from the load's pairs (fit_pair_terms, and
  /// pairs enough); refit_terms() keeps term_fit_ the fit of the current sums (nothing when it
  /// does not apply), called whenever the sums or decide_term_fit() change, not every tick.
  bool fits_pair_terms() const;
  void refit_terms();
  /// The sums of the load's pairs (per gear, the pair terms', their snapshots) start empty.
  void clear_load_sums();
  /// Whether the fit applies to the load whose belief starts now (term_fit_applies_).
  void decide_term_fit();
  /// The regression's state with the fit's shift of the mass (and its interval).
  RegressorState with_term_shift(RegressorState state) const;
  /// A declared known mass becomes the belief's start.
  void begin_known_mass();
  /// The known mass as the published estimate.
  void publish_known_mass();
  /// The published 95 % interval is within converged_halfwidth_fraction of the mass.
  bool published_narrow() const;
  /// A completed standstill window's mass (a first window or a load change).
  void on_static_mass(const StaticMass& static_mass, StepResult* result);
  /// The first step after restore(): after a power cycle the mass starts afresh.
  void begin_after_restore(const Sample& sample);
  /// The load-change monitor's challenger becomes the belief (a load change seen in motion).
  void adopt_challenger();
  /// The drive since the last long stop but one ended in a suspicion a change explains best.
  bool ended_drive_read_another_load() const;
  /// Keeps the belief without that drive, until a later drive tells whether its load is gone.
  void hold_interlude();
  /// Copies the kind of regressor in use from one pair of slots to another.
  void copy_regressor(const RlsEstimator& rls, const BayesEstimator& bayes, RlsEstimator* rls_to,
                      BayesEstimator* bayes_to) const;
  /// At a later stop: the belief without the held drive again, if the load went back.
  bool judge_interlude();
  /// Offer the tick's extractions to the supervisor.
  void offer_pairs(const Sample& sample, StepResult* result);
  /// A pair the belief is fitted on, into the interval's model-term sensitivities.
  void add_to_sensitivities(const RegressionPair& pair);
  /// A pair the belief accepted, into the current load's gear sums.
  void add_to_load_sums(const Extraction& extraction, const PairEvent& event);
  /// The load-change monitor's own extractions (its quicker differencing) to its challenger.
  void offer_monitor_pairs(const Sample& sample);
  /// Forget what the extractors learnt of the load; `reference_mass_kg` (> 0) becomes their gates'.
  void reset_extractors(double reference_mass_kg);
  void refresh_estimate(const Sample& sample);
  /// The estimate's belief and status from the regressor (inputs as of the last step).
  void refresh_belief();
  /// The belief over every accepted pair: the Bayes posterior with its open batch (conjugacy
  /// makes it the posterior a batch boundary would give; the innovation gate keeps the batch's).
  RegressorState belief_state() const;
  /// The extractors' reference mass (their noise and gates) follows their own beliefs.
  void follow_beliefs();
  /// A copy of the Bayes estimator with its open batch closed into the posterior.
  BayesEstimator closed_bayes() const;
  /// While the driveline lag is unknown: the belief with the longitudinal pairs held for it, at
  /// the lag the evidence so far points to, and the lag's uncertainty in its interval. False
  /// (and `*out` untouched) when no held pair passes the gates at that lag.
  bool provisional_state(RegressorState* out) const;
  /// The regression's state into estimate_, with the model error and the plausibility check.
  void publish_state(const RegressorState& state);
  /// Half the published 95 % interval of a belief: the regression's and the model error's.
  double published_half_width(const RegressorState& state) const;
  void span_challenger();
  /// How likely the last long stop changed the load (load_change_odds.hpp).
  double probability_load_changed(const RegressorState& challenger) const;
  /// mass_model_std_kg for a mass (see Estimate).
  double model_std_kg(double mass_kg) const;
  /// The part of it that two readings of one load do not share: all but the lumped scale's.
  double unshared_model_std_kg(double mass_kg) const;
  /// The model error with the lumped scale's variance and the floor's relative std given.
  double model_std_kg(double mass_kg, double scale_variance, double floor) const;

  PipelineParams params_;
  StaticInitializer static_init_;
  LoadChangeMonitor load_monitor_;
  LongitudinalExtractor longitudinal_;
  LateralExtractor lateral_;
  LongitudinalExtractor monitor_longitudinal_;  ///< the load monitor's (its own differencing)
  LateralExtractor monitor_lateral_;
  Supervisor supervisor_;
  RlsEstimator rls_;
  BayesEstimator bayes_;
  MassRegressor* regressor_;
  /// Of the belief's longitudinal pairs: to the rotating masses and to the converter's map.
  PairTermSensitivity rotating_sensitivity_{&RegressionPair::rotating_n};
  PairTermSensitivity converter_sensitivity_{&RegressionPair::converter_n};
  /// The belief's pairs per gear: since its load began (the learnt gear masses' evidence), and
  /// over every load (the interval's sensitivities to them, as rotating_sensitivity_).
  GearPairSums load_sums_;
  GearPairSums interval_sums_;
  GearPairSums sums_before_stop_;  ///< load_sums_ when the load monitor's challenger started
  /// The belief's pairs since its load began, for the errors of its modelled terms (and their
  /// snapshot, as sums_before_stop_).
  PairTermSums term_sums_;
  PairTermSums term_sums_before_stop_;
  /// Decided when the load's belief starts: the fit applies to a load whose belief began with
  /// nothing learnt about the car (fit_pair_terms).
  bool term_fit_applies_ = false;
  PairTermFit term_fit_;
  RegressorState belief_before_stop_;  ///< the belief when the load monitor's challenger started
  /// The regressor then (the kind in use): what a held drive's belief would return to; valid
  /// while before_stop_saved_ (not after a restore or an adoption).
  RlsEstimator rls_before_stop_;
  BayesEstimator bayes_before_stop_;
  bool before_stop_saved_ = false;
  /// A drive held while a later one tells whether its load is gone (hold_interlude): the
  /// belief without it, that belief's state and what the held drive read.
  bool interlude_pending_ = false;
  RlsEstimator rls_without_interlude_;
  BayesEstimator bayes_without_interlude_;
  GearPairSums sums_without_interlude_;
  PairTermSums term_sums_without_interlude_;
  RegressorState belief_without_interlude_;
  RegressorState interlude_reading_;
  double pair_information_;          ///< RegressionPair::information of every extracted pair
  double monitor_pair_information_;  ///< the same for the load monitor's pairs
  bool has_prior_ = false;
  bool has_plausible_ = false;  ///< an estimate of the current load was plausible
  StatusReason prior_reason_ = StatusReason::kWaitingForStandstill;
  MassPrior prior_;
  bool has_reference_ = false;
  double reference_deflection_m_ = 0.0;
  double reference_deflection_std_m_ = 0.0;
  double reference_grade_accel_mps2_ = std::numeric_limits<double>::quiet_NaN();
  bool restore_pending_ = false;  ///< restore() happened, no step since
  TimeUs restored_time_us_ = 0;   ///< the snapshot's time
  bool load_unchecked_ = false;   ///< a power cycle after restore(), no prior since
  LearntScale learnt_;
  LearntGearMasses gear_masses_;
  /// The gear masses this drive's pairs are corrected with: what was learnt up to its start. A
  /// drive's own evidence takes effect at the next power cycle, so that one stretch of one load
  /// never corrects the next load of the same drive (a tractor's solo stretch its coupled one).
  LearntGearMasses applied_gear_masses_;
  long published_gear_revision_ = -1;  ///< gear_masses_'s revision in estimate_
  long published_tyre_revision_ = -1;  ///< tyre_watch_'s revision in estimate_
  /// The current load's standstill reading, while it holds; a snapshot saves its evidence so
  /// far, which a restored pipeline holds until the load ends.
  StaticAnchor static_anchor_;
  TyreWatch tyre_watch_;
  LaunchIntegrator launches_;
  KnownMass known_mass_;
  KnownMass declared_;       ///< active: declared, taken at the next step
  double pair_scale_ = 1.0;  ///< kappa the belief's longitudinal pairs are divided by
  Estimate estimate_;
};

}  // namespace vmass

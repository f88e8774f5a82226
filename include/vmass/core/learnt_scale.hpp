// LearntScale: the vehicle's lumped longitudinal scale kappa, learnt across drives.
//
// With a datasheet config, the wheel-torque signal's scale, the rolling radius and the body
// pitch scale every traction pair's force-to-acceleration ratio by one factor that no single
// drive can tell from the mass: the pairs read kappa * M. kappa is a constant of the car, and
// every drive whose mass is known independently (a known mass the user declared: a weighbridge
// ticket, "empty, driver only") measures it: log kappa = log(M_dynamic / M_known). The belief
// in log kappa is normal; it starts from the datasheet (the declared accuracies) and each
// drive's evidence narrows it. The pipeline divides every longitudinal pair's force by kappa.
//
// Robust (a wrong ticket, someone who got in at the weighbridge): evidence more than
// outlier_sigma from the belief counts less (Huber), and the belief is not moved by one alone.
// A change of the car (new tyres, a retrofit): two such pieces of evidence in a row on the same
// side, consistent with each other, restart the belief from them. Drift (tyre wear): each power
// cycle widens the belief a little. New tyres declared by the workshop (tyres_changed): the
// radius moved by an amount nobody measured, so the belief widens by its uncertainty, keeping
// its mean, and the static anchors start again.
//
// Static anchors (a car whose deflection sensor reads its load, StaticAnchor): each drive's
// pairs against the standstill reading of that load are evidence too, but every reading of the
// car shares one error, the kerb mass's (fuel, options), which no number of drives averages
// away. So they are kept apart, as the weighted mean of their evidence (each weighed by its own
// precision: a load whose position is unknown counts little, the driver alone much) whose
// variance never falls below the shared part. They join the datasheet's belief until a known
// mass is declared; from then on the known masses alone make it, until new tyres: then the
// anchors read since the change join the widened belief until the next known mass.
//
// Pure; not thread-safe (one owner).
#pragma once

#include <cstdint>
#include <string>

#include "vmass/core/tyre_watch.hpp"
#include "vmass/core/vehicle_params.hpp"

namespace vmass {

struct LearningParams {
  /// Per power cycle, the std of the random walk of log kappa (tyre wear, ageing).
  double drift_std_per_drive = 0.002;
  /// Evidence further than this many sigma from the belief is an outlier.
  double outlier_sigma = 3.0;
  /// A drive's evidence counts only from this many longitudinal pairs on ...
  long min_evidence_pairs = 100;
  /// ... and with the regression's own relative std of the mass below this. The evidence's
  /// variance holds that std, so a wide drive counts little; the gate only keeps out drives
  /// whose regression barely started (3 % left 9 of 84 known-mass drives of the lifetime
  /// instrument without evidence, 6 % left 1).
  double max_evidence_std_fraction = 0.06;
  /// At a known mass the regression restarts from it with this relative std: vague, so that
  /// the drive's pairs, not the declaration, make the evidence.
  double anchor_prior_std_fraction = 0.3;
  /// The part of the model-error floor (EstimatorParams::model_error_std_fraction) that differs
  /// from one drive of the car to the next. The rest is the car's own (its aero, rolling and
  /// pitch datasheet errors, its driveline's residue): every drive reads it alike, so the kappa
  /// a known mass or a static anchor measures holds it, and it is not counted again in that
  /// evidence or in the interval of a drive that uses the learnt kappa. Measured on both
  /// populations' fresh drives: a car's error moves from drive to drive by about what the
  /// regressions' own std says. With 0.5 %, a drive is more than 1.96 sigma from the car's
  /// other drives on 3.2 % of cars' drives and 5.0 % of tractors' (docs/estimator.md).
  double drive_error_std_fraction = 0.005;
  /// |log kappa| beyond this is not a scale error but a wrong config or a wrong declaration:
  /// such evidence, or a saved belief, is refused.
  double max_abs_log_scale = 0.25;
  /// Learn each gear's effective rotating mass from how the gears read across drives
  /// (LearntGearMasses).
  bool learn_gear_masses = true;
  /// ... a gear counts in a drive's evidence from this many of its pairs.
  long min_gear_evidence_pairs = 20;
  /// New tyres (tyres_changed): the relative std of the rolling radius's change. Worn tread
  /// replaced by new is +1 to +3 % of the radius; a seasonal set or another size moves it either
  /// way. The mean is kept: the change's size depends on how worn the old set was.
  double tyre_change_std_fraction = 0.02;
  /// New tyres told by the launches and stops (TyreWatch).
  TyreWatchParams tyre_watch;

  std::string validate() const;
};

/// The relative variance of kappa the config declares (its datasheet belief): the torque
/// signal's scale and the rolling radius (uniform within their declared bounds) and the
/// accelerometer's pitch; with a derived overall ratio, the driveline efficiency too.
double declared_scale_variance(const VehicleParams& vehicle);

/// The persisted belief in log kappa (plain values).
struct LearntScaleState {
  double log_scale = 0.0;
  double log_scale_var = 0.0;  ///< > 0
  long evidence = 0;           ///< drives whose evidence was taken
  long changes = 0;            ///< changes of the car detected
  /// The last evidence was an outlier: its sign (+1/-1, 0 none), value and variance.
  long pending_outlier_sign = 0;
  double pending_log_scale = 0.0;
  double pending_var = 0.0;
  /// Static anchors: sums of their evidence x, each weighed by w = 1 / its own variance, and
  /// of w c, c the relative std every reading of the car shares.
  double anchor_weight = 0.0;
  double anchor_weighted_log_scale = 0.0;
  double anchor_weighted_common_std = 0.0;
  long anchors = 0;       ///< drives whose static anchor was taken
  long tyre_changes = 0;  ///< new tyres declared (tyres_changed)
  /// Known masses taken since the last tyre change (all of them without one): the anchors join
  /// the belief while there is none.
  long evidence_since_tyres = 0;
};

enum class ScaleEvidence : std::uint8_t {
  kTaken,         ///< consistent with the belief
  kDownweighted,  ///< an outlier: taken with less weight, remembered
  kChange,        ///< the second outlier in a row on that side: the belief restarted
  kRefused,       ///< not finite, or beyond max_abs_log_scale
};

class LearntScale {
 public:
  /// prior_std: the relative std of kappa the config declares (torque scale, radius, pitch).
  LearntScale(const LearningParams& params, double prior_std);

  double scale() const;  ///< kappa, the belief's median (known masses and static anchors)
  /// The belief's relative std of kappa (the std of log kappa).
  double relative_std() const;
  double log_scale() const;      ///< the belief's mean of log kappa
  double log_scale_var() const;  ///< and its variance
  /// Something measured it: a known mass or a static anchor.
  bool learnt() const { return state_.evidence > 0 || state_.anchors > 0; }
  /// The belief is no longer the config's datasheet: something measured it, or new tyres
  /// widened it (the config's radius is not theirs). The interval then takes its variance.
  bool replaces_datasheet() const { return learnt() || state_.tyre_changes > 0; }
  const LearntScaleState& state() const { return state_; }

  /// One drive's evidence: log kappa and its variance (> 0).
  ScaleEvidence add_evidence(double log_scale, double variance);
  /// The variance add_evidence() would take that evidence with now: its own, an outlier's
  /// inflated one (Huber), or infinity when it would be refused. A change of the car restarts
  /// the belief from two pieces of evidence; this then gives the evidence's own.
  double taken_variance(double log_scale, double variance) const;
  /// One drive's static anchor: log kappa, its own variance (> 0) and the relative std every
  /// reading of the car shares (>= 0). Evidence further than outlier_sigma from the belief is
  /// taken with the variance that puts it there (Huber); refused as add_evidence refuses.
  ScaleEvidence add_anchor(double log_scale, double variance, double common_std);
  /// The vehicle was switched off and on: the belief widens by the drift.
  void drift();
  /// New tyres (a workshop's declaration): the belief widens by tyre_change_std_fraction, the
  /// pending outlier and the static anchors (read on the old tyres) are dropped, and the anchors
  /// read from now on join the belief until the next known mass.
  void tyres_changed();
  /// New tyres measured (TyreWatch): log kappa moved by log_step, with that step's variance.
  /// Everything the belief holds moves with it (the known masses' evidence, the static anchors,
  /// a pending outlier): each measured kappa on the old tyres, which the step carries to the new.
  void tyres_measured(double log_step, double log_step_var);
  /// Back to the datasheet (a user's reset).
  void reset();
  /// false (and nothing changed) when the state is not a belief this class could hold.
  bool restore(const LearntScaleState& state);
  /// "" when the state is one restore() takes, else why not.
  std::string implausible(const LearntScaleState& state) const;

 private:
  void take(double log_scale, double variance);
  /// The anchors are part of the belief: some, and no known mass yet.
  bool anchors_join() const;
  /// The static anchors' mean of log kappa and its variance (anchors > 0).
  double anchor_mean() const;
  double anchor_var() const;

  LearningParams params_;
  double prior_var_;
  LearntScaleState state_;
};

}  // namespace vmass

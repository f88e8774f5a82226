// Estimate: what the pipeline publishes at each tick: mass, model imprecision mu, the 95%
// interval, a status with its reason, and availability per block.
//
// Status:
//   initialising  no belief yet (no standstill window, not driving)
//   static_only   the static initialisation (eq. 3) only; no dynamic event used yet
//   converging    dynamic events are refining the estimate
//   converged     the published 95% interval's half-width is at most
//                 converged_halfwidth_fraction (5 %) of the mass, the regression's own part
//                 below converged_ci_halfwidth_fraction (1 %) (more driving would not narrow
//                 it), and no load change is undecided; `converging (model_limited)` when only
//                 the published width is missing: what the config leaves unknown about the car
//                 (the lumped scale, the rotating masses) is wider than that, and only a known
//                 mass, not more driving, narrows it
//   degraded      inputs an enabled block needs are stale or invalid at this tick; the last
//                 estimate is held
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <string_view>

#include "vmass/core/gear_pair_sums.hpp"
#include "vmass/core/regression_pair.hpp"
#include "vmass/core/sample.hpp"
#include "vmass/core/supervisor.hpp"

namespace vmass {

enum class EstimateStatus : std::uint8_t {
  kInitialising = 0,
  kStaticOnly,
  kConverging,
  kConverged,
  kDegraded
};

enum class StatusReason : std::uint8_t {
  kWaitingForStandstill = 0,  ///< initialising: no standstill window yet
  kStaticInitialised,         ///< static mass from the deflection, no event yet
  kLoadChanged,               ///< re-initialised at standstill: the load changed
  kNoStaticPrior,             ///< driving started before any standstill: prior = empty mass
  kRefining,                  ///< events are being used
  kIntervalNarrow,            ///< converged
  kInputsInvalid,             ///< degraded: see invalid_inputs
  kRestored,                  ///< state restored from a saved estimate
  kNoLoadSensor,              ///< no deflection sensor that carries the load (none, or a
                              ///< self-levelling axle): prior = empty + half the capacity
  kLoadChangeSuspected,       ///< converging: since a stop, the drive disagrees with the belief
                              ///< (LoadChangeMonitor::suspects); the interval spans both,
                              ///< the mass is the drive's since the stop
  kLagProvisional,            ///< converging: the driveline lag is not identified yet; the
                              ///< estimate takes the held pairs at the best fit so far, its
                              ///< interval what the lag's uncertainty does to the mass
  kLoadUnchecked,             ///< initialising: restored after the vehicle was off, when the
                              ///< load may have changed; the mass starts afresh at the first
                              ///< standstill (or with the drive, without a load sensor)
  kMassImplausible,           ///< degraded: no estimate of this load has been in the plausible
                              ///< band (plausible_band.hpp); no mass is published, and
                              ///< implausible_mass_kg says what the estimator holds
  kKnownMass,                 ///< converged: the user declared the load's mass (KnownMass)
  kModelLimited,              ///< converging: the regression has converged, but the published
                              ///< interval (its model error) is wider than converged allows
};

std::string_view status_name(EstimateStatus s);
std::string_view reason_name(StatusReason r);

struct Estimate {
  TimeUs time_us = 0;
  double mass_kg = 0.0;
  double mu_n = 0.0;
  double mass_std_kg = 0.0;
  double ci_low_kg = 0.0;
  double ci_high_kg = 0.0;
  double initial_mass_kg = 0.0;  ///< the static (or empty-mass) prior of the current load
  /// Where initial_mass_kg came from: static_initialised or load_changed (eq. 3 at a
  /// standstill), no_static_prior (driving began before any standstill), no_load_sensor (the
  /// car has no deflection sensor that reads the load), restored (a saved state);
  /// waiting_for_standstill while there is none.
  StatusReason prior_reason = StatusReason::kWaitingForStandstill;
  long pairs_used = 0;
  EstimateStatus status = EstimateStatus::kInitialising;
  StatusReason reason = StatusReason::kWaitingForStandstill;
  InputMask invalid_inputs = 0;  ///< inputs needed but invalid at this tick
  std::array<BlockCounters, kBlockCount> blocks{};

  bool mass_known = false;  ///< false until a prior exists (static or empty-mass), and while no
                            ///< estimate of the load has been plausible (kMassImplausible)

  /// Of mass_std_kg, what no amount of driving averages away: the declared accuracy of the
  /// torque scale, the rolling radius and the rotating masses, the accelerometer's pitch, the
  /// model-error floor. The 95 % interval holds it in quadrature with the regression's; the
  /// status converges on the regression's part alone.
  double mass_model_std_kg = 0.0;
  /// False when the regression left the plausible band [plausible_low_kg, plausible_high_kg]
  /// (below the empty mass or above the maximum permissible mass, with margins): mass_kg and
  /// the interval then hold the last plausible estimate and implausible_mass_kg says where the
  /// regression went.
  bool plausible = true;
  double implausible_mass_kg = 0.0;
  double plausible_low_kg = 0.0;
  double plausible_high_kg = 0.0;
  /// The longitudinal block's identified delay of a_x behind the force (-1: not yet) and its
  /// measured noise (-1: not yet).
  double driveline_lag_s = -1.0;
  double accel_noise_std_mps2 = -1.0;
  double force_noise_std_n = -1.0;
  /// What is learnt about the car across drives (LearntScale): the lumped longitudinal scale
  /// the pairs' force is divided by, its relative std, the drives whose known mass was
  /// evidence of it and the changes of the car detected.
  double learnt_scale = 1.0;
  double learnt_scale_std = 0.0;
  long learnt_evidence = 0;
  long learnt_changes = 0;
  long learnt_anchors = 0;               ///< drives whose standstill reading anchored the scale
  long learnt_tyre_changes = 0;          ///< new tyres declared (LearntScale::tyres_changed)
  long learnt_evidence_since_tyres = 0;  ///< of learnt_evidence, those since the last ones
  bool known_mass = false;               ///< the published mass is a mass the user declared
  /// Each gear's rotating mass learnt across drives (LearntGearMasses): the correction of the
  /// config's mass of gear i + 1 and its std, kg, for learnt_gears gears; the drives it rests on.
  int learnt_gears = 0;
  std::array<double, kMaxLearntGears> learnt_gear_correction_kg{};
  std::array<double, kMaxLearntGears> learnt_gear_std_kg{};
  long learnt_gear_drives = 0;
  /// The tyre watch (TyreWatch): the launches and stops it holds since the last change (this
  /// drive's included), the undeclared changes it told, and the largest step of the speed
  /// signal's scale the window holds (a fraction, and in its std: a change beyond change_sigma;
  /// beyond suspect_sigma suspected, and the interval holds it meanwhile).
  long tyre_watch_launches = 0;
  long tyre_watch_stops = 0;
  long tyre_watch_changes = 0;
  double tyre_watch_step = 0.0;
  double tyre_watch_step_sigma = 0.0;
  bool tyre_watch_suspected = false;
  /// The drive's pair-term fit (PairTermFit) while it applies: the rotating masses' error c_rot
  /// and the converter map's c_conv (fitted only when some pair held its multiplication), each
  /// with its std, the pairs fitted, and the mass's shift with the std the terms leave, kg.
  bool pair_fit_applies = false;
  bool pair_fit_converter_multiplied = false;
  long pair_fit_pairs = 0;
  double pair_fit_rotating_error = 0.0;
  double pair_fit_rotating_error_std = 0.0;
  double pair_fit_converter_error = 0.0;
  double pair_fit_converter_error_std = 0.0;
  double pair_fit_shift_kg = 0.0;
  double pair_fit_shift_std_kg = 0.0;

  bool has_mass() const { return mass_known; }
  /// Human-readable reason, e.g. "inputs invalid: speed, yaw_rate" (allocates; not for hot paths).
  std::string describe_reason() const;
  /// Why the regression's mass was refused, e.g. "12000 kg above the plausible band (up to
  /// 3615 kg)" (allocates; not for hot paths).
  std::string describe_rejection() const;
};

}  // namespace vmass

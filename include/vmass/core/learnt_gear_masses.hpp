// LearntGearMasses: each gear's effective rotating mass, learnt across drives.
//
// A pair in gear g reads the mass plus delta_g, the error of the rotating mass the config gives
// for g: the engine's and the gearbox's inertia reflected through the gear (+-30 % on a
// datasheet, one factor for every gear) and a residue of the driveline that is a property of
// the car (a truck's low gears read thousands of kg less than the config's, drive after drive).
// A drive in one gear mix therefore reads another mass than a drive in another: a truck's urban
// drive in gears 2-6 ends 7 % lower than its highway drive (tractor-200003: -10.2 and -3.5 %).
//
// One drive cannot tell delta from the mass (the gears it uses are too few and too alike), but
// every drive tells how its gears differ from each other, and the car meets many gear mixes.
// So the belief is over the vector delta (normal, gears x gears): its prior is the datasheet's
// error, common to all gears and each gear's own in equal parts (std accuracy / sqrt(3) x the
// config's mass of the gear, each). A drive's evidence is each gear's effective mass over the
// drive (its pairs' weighted reading, with a floor of the model's error), with the drive's mass
// unknown: only the differences between gears count, and what no difference can show (a shift
// common to every gear) stays with the prior. The gears whose config mass is small (the top
// ones) are pinned by their prior, the low ones learn. The pipeline subtracts the learnt delta_g
// dv' from each pair of gear g, and the interval holds what is left of the belief. A drive on a
// known mass taught the lumped scale its gear mix's level relative to its mass; the pipeline
// takes that level off the scale (scale_factor), so that the level is removed once, in kg, at
// any mass.
//
// Pure; not thread-safe (one owner).
#pragma once

#include <array>
#include <string>
#include <vector>

#include "vmass/core/gear_pair_sums.hpp"
#include "vmass/core/learnt_scale.hpp"
#include "vmass/core/vehicle_params.hpp"

namespace vmass {

/// The persisted belief (plain values).
struct GearMassesState {
  int gears = 0;  ///< gears learnt; 0 nothing (no per-gear masses in the config)
  std::array<double, kMaxLearntGears> correction_kg{};  ///< the belief's mean of delta_g
  /// Its covariance, kg^2, row-major with stride kMaxLearntGears.
  std::array<double, kMaxLearntGears * kMaxLearntGears> covariance_kg2{};
  long drives = 0;  ///< drives (loads) whose evidence was taken
  /// The gear mix of the drives on a known mass, relative to their mass: per gear, the sum over
  /// them of the mass's sensitivity to the gear's correction (GearPairSums) over the drive's
  /// mass, times the precision of the scale's evidence the drive gave, 1/kg. A drive's evidence
  /// of log kappa holds its mix's level sum_g s_g (delta_g - c_g) / M, c_g the corrections
  /// applied then: the scale holds it as much as the evidence weighs in the scale's mean.
  std::array<double, kMaxLearntGears> reference_share_per_kg{};
  /// The same sum of the level of the corrections applied on those drives, sum_g s_g c_g / M
  /// times the precision (they took that level off already).
  double reference_applied = 0.0;
  /// The scale's precision with that evidence: its datasheet precision plus the evidence's
  /// (0 without a reference).
  double reference_precision = 0.0;
};

class LearntGearMasses {
 public:
  /// rotating_mass_by_gear_kg: the config's (index gear - 1; beyond kMaxLearntGears not learnt);
  /// accuracy_fraction: its declared uniform bound; floor_fraction: the relative error one
  /// drive's reading of a gear has beyond its pairs' noise (the model error); min_gear_pairs: a
  /// gear counts in a drive's evidence from this many pairs.
  LearntGearMasses(const std::vector<double>& rotating_mass_by_gear_kg, double accuracy_fraction,
                   double floor_fraction, long min_gear_pairs);

  int gears() const { return state_.gears; }
  /// Counts the changes of the belief: what shows it is refreshed only when it moves.
  long revision() const { return revision_; }
  bool learnt() const { return state_.drives > 0; }
  const GearMassesState& state() const { return state_; }
  /// The learnt delta of `gear` (1-based), kg; 0 for a gear not learnt.
  double correction_kg(int gear) const;
  /// The factor the lumped scale is multiplied by before the pairs are divided by it: the
  /// known-mass drives' evidence put their gear mix's level (relative to their mass) into the
  /// scale, which the corrections now take off each pair in kg. Relative, so that it holds at
  /// another mass: a level of e kg learnt at M1 and taken off in kg at M2 would leave an error
  /// of e (1/M2 - 1/M1) (-7 % for a truck's 12 -> 27 t with e = 1.5 t). 1 without a reference.
  double scale_factor() const { return scale_factor_; }
  /// Its std, kg (0 for a gear not learnt).
  double correction_std_kg(int gear) const;
  /// A drive on a known mass whose evidence the lumped scale took, with that evidence's variance
  /// and the scale's datasheet variance, its mass and the corrections applied on it: its pairs'
  /// gear mix becomes part of the reference.
  void add_reference(const GearPairSums& sums, double mass_kg, double evidence_variance,
                     double scale_prior_variance, const LearntGearMasses& applied);
  /// The variance the belief in delta leaves in a mass of mass_kg fitted on `sums` with these
  /// corrections and this scale factor, kg^2.
  double mass_variance_kg2(const GearPairSums& sums, double mass_kg) const;

  /// One load's evidence: its regression's pairs per gear and its intercept mu, and its mass
  /// (for the floor). False (nothing changed) when fewer than two gears have enough pairs, or
  /// when the belief it would give is implausible.
  bool add_evidence(const GearPairSums& sums, double mass_kg, double mu_n);
  /// What the belief would be with that evidence (this unchanged).
  LearntGearMasses with_evidence(const GearPairSums& sums, double mass_kg, double mu_n) const;
  /// Back to the datasheet.
  void reset();
  /// "" when the state is one restore() takes, else why not.
  std::string implausible(const GearMassesState& state) const;
  /// false (and nothing changed) when implausible.
  bool restore(const GearMassesState& state);

 private:
  double prior_variance_kg2(int i, int j) const;
  /// scale_factor_ from the state: called by every change of it, so that the pipeline reads a
  /// number.
  void refresh_scale_factor();

  std::array<double, kMaxLearntGears> config_kg_{};
  double std_fraction_ = 0.0;  ///< the config's masses' std per part (common, own)
  double floor_fraction_ = 0.0;
  long min_gear_pairs_ = 1;
  GearMassesState state_;
  long revision_ = 0;
  double scale_factor_ = 1.0;  ///< 1 / (1 + the reference's level) (refresh_scale_factor)
};

/// The learnt gear masses of a vehicle: its per-gear rotating masses, unless the config turns
/// the learning off or derives the ratio (whose plateaus are no gear numbers that hold from
/// drive to drive); then no gear is learnt.
LearntGearMasses learnt_gear_masses_for(const VehicleParams& vehicle,
                                        const LearningParams& learning,
                                        double model_error_std_fraction);

}  // namespace vmass

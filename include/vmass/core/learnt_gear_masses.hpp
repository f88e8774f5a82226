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
// dv' from each pair of gear g, and the interval holds what is left of the belief.
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
  /// The gear mix of the drives on a known mass: per gear, the sum over them of the mass's
  /// sensitivity to the gear's correction (GearPairSums) times the precision of the scale's
  /// evidence the drive gave. Their mass taught the lumped scale with the corrections of that
  /// time: the scale holds their mix's level as much as their evidence weighs in it.
  std::array<double, kMaxLearntGears> reference_share{};
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
  bool learnt() const { return state_.drives > 0; }
  const GearMassesState& state() const { return state_; }
  /// The learnt delta of `gear` (1-based), kg; 0 for a gear not learnt.
  double correction_kg(int gear) const;
  /// What the pipeline subtracts for `gear`: its delta less the level of the known-mass drives'
  /// gear mix that the lumped scale already holds (their mean delta, weighed as their evidence
  /// weighs in the scale), kg.
  double applied_correction_kg(int gear) const;
  /// Its std, kg (0 for a gear not learnt).
  double correction_std_kg(int gear) const;
  /// A drive on a known mass whose evidence the lumped scale took, with that evidence's variance
  /// and the scale's datasheet variance: its pairs' gear mix becomes part of the reference.
  void add_reference(const GearPairSums& sums, double evidence_variance,
                     double scale_prior_variance);
  /// The variance the belief in delta leaves in a mass fitted on `sums` with the applied
  /// corrections, kg^2.
  double mass_variance_kg2(const GearPairSums& sums) const;

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
  /// The level of delta the lumped scale holds, kg (0 without a reference), into offset_kg_:
  /// called by every change of the state, so that the per-pair correction is one subtraction.
  void refresh_offset();

  std::array<double, kMaxLearntGears> config_kg_{};
  double std_fraction_ = 0.0;  ///< the config's masses' std per part (common, own)
  double floor_fraction_ = 0.0;
  long min_gear_pairs_ = 1;
  GearMassesState state_;
  double offset_kg_ = 0.0;  ///< reference's level of delta (refresh_offset)
};

/// The learnt gear masses of a vehicle: its per-gear rotating masses, unless the config turns
/// the learning off or derives the ratio (whose plateaus are no gear numbers that hold from
/// drive to drive); then no gear is learnt.
LearntGearMasses learnt_gear_masses_for(const VehicleParams& vehicle,
                                        const LearningParams& learning,
                                        double model_error_std_fraction);

}  // namespace vmass

// StaticInitializer: the initial mass from the rear-right suspension deflection (paper eq. 3),
// and the detection of a load change at standstill.
//
//   M_initial = M_idle + 2 l F_rr(z_mean) / (l_f g)                              eq. (3)
// where F_rr is SuspensionParams::wheel_force_n (the linear c (z - z0) of the paper, or the
// calibrated progressive curve) and z_mean is the deflection averaged over a standstill window.
//
// Eq. (3) puts the added load at the centre of gravity and shares it equally between the rear
// wheels. A load at x behind the front axle and y to the left (of a track t) really adds
//   dF_rr = dm g (x / l) (1/2 - y / t),  so eq. (3) reads  dM_eq3 = dm q,  q = (x / l_f)(1 - 2 y /
//   t)
// (a boot load reads 2.5-3x heavy, the driver on the left about half). Where the payload sits is
// not known, so the prior takes the added mass as dm = dM_eq3 / q with x uniform over
// payload_x_range (fractions of l: front seats to boot by default) and y / t uniform over
// payload_y_range: its mean E[1/q] dM_eq3 (about 0.6 dM_eq3 on a front-heavy car) and its
// spread Std[1/q] |dM_eq3| join the base uncertainty prior_std_fraction_of_empty * M_idle (the
// kerb mass is known to a few percent: fuel, options) and prior_std_kg. A config that knows
// where its payload goes narrows the ranges.
//
// A standstill window starts settle_s after the speed falls below standstill_speed_mps and
// completes after standstill_window_s; a window whose deflection spread exceeds
// max_deflection_std_m (someone is loading, the body still rocks) is discarded and a new one
// starts. The first completed window gives the initial mass. Each later window is compared with
// the reference (the window that gave the current mass) when it stands on the same grade
// (a_x at rest within max_grade_change_mps2): the load changed when the eq. (3) mass moved by
// more than max(min_load_change_kg, min_load_change_fraction M_idle, load_change_sigma x the
// windows' noise); a grade difference, pitch and creep move the deflection by far less.
// A reported change carries the added mass (with the same payload prior) so that the caller can
// shift its belief by it instead of forgetting what the drive taught.
//
// Pure: time comes from the samples. Not thread-safe; no allocation.
#pragma once

#include <limits>
#include <optional>
#include <string>

#include "vmass/core/mass_prior.hpp"
#include "vmass/core/sample.hpp"
#include "vmass/core/vehicle_params.hpp"

namespace vmass {

struct StaticInitParams {
  double standstill_speed_mps = 0.05;
  double settle_s = 1.0;
  double standstill_window_s = 2.0;
  double max_deflection_std_m = 0.002;
  double prior_std_kg = 40.0;                  ///< base std of the static mass,
  double prior_std_fraction_of_empty = 0.025;  ///< or this fraction of M_idle if larger
  double payload_x_min_fraction = 0.45;        ///< where payload may sit, in fractions of l behind
  double payload_x_max_fraction = 1.15;        ///< the front axle (front seats .. boot)
  double payload_y_max_fraction = 0.25;        ///< and |y| / track (seats beside the centre line)
  double out_of_range_prior_std_kg = 250.0;    ///< beyond the linear/calibrated range
  double no_static_prior_std_kg = 400.0;       ///< no deflection and no maximum mass known
  double mu_prior_std_n = 300.0;               ///< prior std of the model imprecision mu
  double load_change_sigma = 6.0;
  double min_load_change_kg = 50.0;        ///< eq. (3) mass change that counts as a load change,
  double min_load_change_fraction = 0.03;  ///< or this fraction of M_idle if larger
  double max_grade_change_mps2 = 0.05;     ///< |a_x| difference at rest (0.05 m/s^2 ~ 0.5 %)

  std::string validate() const;
};

/// A completed standstill window that changed the believed mass.
struct StaticMass {
  TimeUs time_us = 0;
  MassPrior prior;
  double deflection_m = 0.0;        ///< window mean
  double deflection_std_m = 0.0;    ///< window spread
  double grade_accel_mps2 = 0.0;    ///< mean a_x over the window (g sin(grade)); NaN if unknown
  double added_mass_kg = 0.0;       ///< prior mass - M_idle (payload-position prior applied)
  bool load_changed = false;        ///< false for the first initialisation
  double mass_change_kg = 0.0;      ///< load change: mass added since the reference window
  double mass_change_std_kg = 0.0;  ///< ... and its uncertainty
  bool beyond_calibrated_range = false;
};

class StaticInitializer {
 public:
  StaticInitializer(const VehicleParams& vehicle, const SuspensionParams& suspension,
                    const StaticInitParams& params);

  /// Feed one sample; returns a StaticMass when a window completed and the mass is new
  /// (first initialisation or load change).
  std::optional<StaticMass> step(const Sample& sample);

  /// Eq. (3): mass for a mean deflection, and whether it lies beyond the calibrated range.
  double mass_from_deflection_kg(double deflection_m) const;
  /// The prior for a deflection, with the wider std beyond the calibrated range.
  StaticMass static_mass_for(double deflection_m, double deflection_std_m) const;
  /// The prior used when driving starts before any standstill window, or without a deflection
  /// sensor: the empty mass plus half the payload capacity (when the maximum permissible mass is
  /// known), its spread the capacity's uniform std; else no_static_prior_std_kg.
  MassPrior no_static_prior() const;
  /// E[1/q] and Std[1/q] of the payload-position prior (see the header).
  double payload_factor_mean() const { return factor_mean_; }
  double payload_factor_std() const { return factor_std_; }
  /// The std every reading shares: the kerb mass (fuel, options), max(prior_std_kg,
  /// prior_std_fraction_of_empty x M_idle).
  double base_std_kg() const;

  bool initialised() const { return reference_.has_value(); }
  /// The next settled window becomes the reference without a comparison (the load the
  /// reference was measured at may have changed unseen: a power cycle).
  void forget_reference() { reference_.reset(); }
  /// Restore after a restart (persistence): the reference deflection of the saved estimate.
  void restore_reference(double deflection_m, double deflection_std_m,
                         double grade_accel_mps2 = std::numeric_limits<double>::quiet_NaN());
  bool standing() const { return standing_; }

 private:
  void restart_window();
  /// A settled window (mean deflection, its spread, the grade) against the reference: the mass
  /// when it is new (a first window or a load change).
  std::optional<StaticMass> judge_window(TimeUs time_us, double mean, double spread, double grade);

  VehicleParams vehicle_;
  SuspensionParams suspension_;
  StaticInitParams params_;
  double factor_mean_ = 1.0;
  double factor_std_ = 0.0;

  bool standing_ = false;
  TimeUs standing_since_us_ = 0;
  TimeUs window_start_us_ = 0;
  bool window_open_ = false;
  long window_count_ = 0;
  double window_mean_ = 0.0;
  double window_m2_ = 0.0;
  long grade_count_ = 0;
  double grade_sum_ = 0.0;

  struct Reference {
    double deflection_m;
    double deflection_std_m;
    double grade_accel_mps2;  ///< NaN when a_x was not valid
  };
  std::optional<Reference> reference_;
};

}  // namespace vmass

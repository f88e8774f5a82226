// StaticInitializer: the initial mass from the rear-right suspension deflection (paper eq. 3),
// and the detection of a load change at standstill.
//
//   M_initial = M_idle + 2 l F_rr(z_mean) / (l_f g)                              eq. (3)
// where F_rr is SuspensionParams::wheel_force_n (the linear c (z - z0) of the paper, or the
// calibrated progressive curve) and z_mean is the deflection averaged over a standstill window.
//
// A standstill window starts settle_s after the speed falls below standstill_speed_mps and
// completes after standstill_window_s; a window whose deflection spread exceeds
// max_deflection_std_m (someone is loading, the body still rocks) is discarded and a new one
// starts. The first completed window gives the initial mass. Each later window is compared with
// the reference (the window that gave the current mass): when its mean moved by more than
// max(load_change_sigma * noise, min_load_change_m), the load changed and a new initial mass is
// reported, so that the caller restarts the regressors.
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
  double prior_std_kg = 40.0;                 ///< std of the static mass in the calibrated range,
  double prior_std_fraction_of_added = 0.15;  ///< plus this fraction of the added mass: eq. (3)
                                              ///< puts the load at the centre of gravity
  double out_of_range_prior_std_kg = 250.0;   ///< beyond the linear/calibrated range
  double no_static_prior_std_kg = 400.0;      ///< driving before any standstill window
  double mu_prior_std_n = 300.0;              ///< prior std of the model imprecision mu
  double load_change_sigma = 6.0;
  double min_load_change_m = 0.0005;
  double max_grade_change_mps2 = 0.1;  ///< |a_x| difference at rest (0.1 m/s^2 ~ 1 % grade)

  std::string validate() const;
};

/// A completed standstill window that changed the believed mass.
struct StaticMass {
  TimeUs time_us = 0;
  MassPrior prior;
  double deflection_m = 0.0;      ///< window mean
  double deflection_std_m = 0.0;  ///< window spread
  double grade_accel_mps2 = 0.0;  ///< mean a_x over the window (g sin(grade)); NaN if unknown
  double added_mass_kg = 0.0;     ///< M_initial - M_idle
  bool load_changed = false;      ///< false for the first initialisation
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
  /// The prior used when driving starts before any standstill window.
  MassPrior no_static_prior() const;

  bool initialised() const { return reference_.has_value(); }
  /// Restore after a restart (persistence): the reference deflection of the saved estimate.
  void restore_reference(double deflection_m, double deflection_std_m,
                         double grade_accel_mps2 = std::numeric_limits<double>::quiet_NaN());
  bool standing() const { return standing_; }

 private:
  void restart_window();

  VehicleParams vehicle_;
  SuspensionParams suspension_;
  StaticInitParams params_;

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

// PlateauDetector: finds the standstill plateaus of a static ballast test in the deflection
// signal itself, so that a recording of the whole test (samples CSV today, a candump log once
// the CAN signal mapping exists) can be calibrated from the list of ballast masses alone.
//
// Input: a generic time series (time_s, deflection_m, optional speed_mps). Steps:
//   1. noise:   sigma = max(min_noise_m, 1.4826 median|z_i - z_{i-1}| / sqrt(2))
//      (the differences cancel the slow level, so steps and ramps barely move the median);
//   2. steady:  sample i is steady when every sample of the centred window
//      [t_i - window_s/2, t_i + window_s/2] is standing (|v| <= standstill_speed_mps, or no
//      speed known), the window lies inside the record without gaps, the window's standard
//      deviation is <= steady_std_factor * sigma (a ramp of slope a has std a w / sqrt(12)),
//      and the means of its two halves differ by <= steady_drift_sigma * 2 sigma / sqrt(n)
//      (n samples in the window; this catches slow ramps and creep the std test lets pass);
//   3. runs:    maximal sequences of steady samples without a time gap (> 5 sample periods);
//   4. settling transients are rejected: the first settle_s of every run is dropped, then the
//      run's level L is the median of its second half, and samples are dropped from the start
//      until the mean of the next window_s first comes within 3 sigma / sqrt(n_window) of L;
//   5. runs shorter than min_plateau_s after trimming are discarded (a note says so, unless the
//      run was shorter than settle_s, as inside a ramp), and consecutive plateaus closer than
//      min_step_m are one plateau interrupted by a disturbance (someone leaning on the car) and
//      are merged;
//   6. each plateau's deflection is the mean of its kept samples.
// steps_from_plateaus() then pairs plateaus with the ballast masses in time order and fails,
// listing what it found, when the counts differ.
//
// Pure functions; thread-safe.
#pragma once

#include <limits>
#include <string>
#include <vector>

#include "vmass/calibrate/ballast_step.hpp"

namespace vmass::calibrate {

/// One sample of the generic deflection time series.
struct DeflectionPoint {
  double time_s = 0.0;
  double deflection_m = 0.0;
  double speed_mps = std::numeric_limits<double>::quiet_NaN();  ///< NaN: unknown (standing)
};

struct PlateauParams {
  double standstill_speed_mps = 0.05;
  double window_s = 1.0;            ///< steadiness window
  double steady_std_factor = 2.0;   ///< window std must stay below this times the noise
  double steady_drift_sigma = 5.0;  ///< half-window means must agree within this many std
  double min_noise_m = 1e-5;        ///< floor on the noise estimate (sensor resolution)
  double settle_s = 1.0;            ///< always dropped at the start of a steady run
  double min_plateau_s = 3.0;       ///< shortest plateau kept, after trimming
  double min_step_m = 3e-4;         ///< plateaus closer than this are the same load

  /// "" or a message naming the key (plateau.*) and the violated bound.
  std::string validate() const;
};

struct Plateau {
  double start_s = 0.0;  ///< first kept sample
  double end_s = 0.0;    ///< last kept sample
  double deflection_m = 0.0;
  double deflection_std_m = 0.0;
  int sample_count = 0;
};

struct PlateauDetection {
  std::vector<Plateau> plateaus;   ///< in time order
  double noise_std_m = 0.0;        ///< sigma of step 1
  std::vector<std::string> notes;  ///< discarded short runs, merges
  std::string error;               ///< non-empty: the series cannot be used (NaN, time order)
  bool ok() const { return error.empty(); }
};

PlateauDetection detect_plateaus(const std::vector<DeflectionPoint>& series,
                                 const PlateauParams& params);

/// Pairs plateaus (time order) with masses (the ballast added at each plateau, same order).
/// "" and *steps filled, or a message that lists the plateaus found.
std::string steps_from_plateaus(const std::vector<Plateau>& plateaus,
                                const std::vector<double>& added_masses_kg,
                                std::vector<BallastStep>* steps);

}  // namespace vmass::calibrate

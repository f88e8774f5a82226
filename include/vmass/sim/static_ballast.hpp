// Static ballast scenario: the paper's static test (Sec. III-B, Fig. 9) for vmass-calibrate.
// The empty car stands on level ground; 8 ballast steps of 100 kg are put in one after the
// other, each ramped in over ramp_s (someone loading) and held for hold_s so that the body
// settles. The ballast sits at the empty car's centre of gravity, as the paper's eq. (2)
// assumes, so each step adds dF_rr = dM g l_f / (2 l) to the rear-right wheel. The simulated
// rear-right suspension (suspension.hpp) has a bump stop about 30 mm above the empty car's
// static compression (about 414 kg of ballast), so the last steps leave the linear range.
//
// Outputs, besides the usual samples.csv / truth.csv / config.yaml:
//   DIR/ballast.csv            added_mass_kg,rear_right_deflection_mm: one row per 100 Hz sensor
//                              sample of each hold, its first settle_s left out (what an engineer
//                              records once a step has settled);
//   DIR/suspension_truth.yaml  the true curve in the sensor's coordinates (what a perfect
//                              calibration finds: the config loader's suspension keys, the
//                              sensor's zero offset included), the sensor noise, and each
//                              step's noise-free mean deflection.
//
// Plain data and pure functions; thread-safe.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "vmass/sim/scenario.hpp"
#include "vmass/sim/simulator.hpp"

namespace vmass::sim {

struct BallastSchedule {
  int steps = 8;               ///< ballast steps after the empty hold
  double step_kg = 100.0;      ///< mass of each step
  double first_hold_s = 20.0;  ///< the empty car
  double ramp_s = 3.0;         ///< each step is put in over this time
  double hold_s = 20.0;        ///< then held
  double settle_s = 5.0;       ///< start of each hold left out of ballast.csv

  double duration_s() const { return first_hold_s + steps * (ramp_s + hold_s); }
  /// Added mass of hold k (0: empty car).
  double added_mass_kg(int k) const { return k * step_kg; }
  /// Time window [first, second) of hold k written to ballast.csv.
  std::pair<double, double> written_window(int k) const;
  std::string validate() const;
};

/// The scenario (name "static_ballast").
Scenario static_ballast_scenario(const BallastSchedule& schedule = {});

/// The truth of a static ballast run, in the deflection sensor's coordinates.
struct BallastTruth {
  double stiffness_n_per_m = 0.0;          ///< c
  double empty_deflection_m = 0.0;         ///< z0: noise-free reading of the empty car
  double progressive_knee_m = 0.0;         ///< z_knee
  double progressive_rate_n_per_m2 = 0.0;  ///< k2
  double knee_added_mass_kg = 0.0;         ///< ballast at the CG that reaches the knee
  double sensor_offset_m = 0.0;            ///< zero offset included in the readings
  double sensor_noise_std_m = 0.0;
  double sensor_resolution_m = 0.0;
  std::vector<double> added_mass_kg;      ///< per hold
  std::vector<double> mean_deflection_m;  ///< noise-free, offset included, over the window
};

BallastTruth ballast_truth(const SimulationResult& result, const BallastSchedule& schedule = {});

/// The text of ballast.csv and of suspension_truth.yaml (the demo team hands them over with the
/// drive, demo_drive.hpp); the schedule must be valid.
std::string ballast_csv(const SimulationResult& result, const BallastSchedule& schedule = {});
std::string suspension_truth_yaml(const SimulationResult& result,
                                  const BallastSchedule& schedule = {});

}  // namespace vmass::sim

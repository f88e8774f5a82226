// DrivelineMode: identifies each gear's torsional mode from the data and applies it to the
// reported force, so that the longitudinal pairs compare the acceleration with the force the
// hub passed on.
//
// The driveline between the reported torque and the hub is a lightly damped spring:
//   T_hub'' + 2 zeta w_n T_hub' + w_n^2 T_hub = w_n^2 T_reported,  w_n = 2 pi f_n(gear)
// Its static gain is 1, but below resonance it amplifies the torque by about
// 1 / (1 - (f / f_n)^2). The pairs' content (the belief's low-pass, its differencing) lies at
// 0.3-0.7 Hz, and a truck's first gear rings at 1.2-2.5 Hz (a car's at 2-4 Hz), so the
// mass read from the reported torque is low by up to 20 % in those gears (docs/estimator.md).
// The lag estimator cannot take this up: it is a gain, not a delay.
//
// Identification: the mode's ringing, after every change of torque, is in the accelerometer.
// Both the reported force and a_x pass the same band-pass (band_low_hz .. band_high_hz, where
// the mode rings and the pairs' band, the grade and the pitch do not), and the force through
// each candidate mode (f_n on a log grid from min_hz to max_hz; "none" is the force itself). On
// each clean tick of a gear, the sums for the correlation of each candidate, taken at each lag
// up to max_lag_s earlier, with the acceleration are accumulated for that gear (each lag's with
// its own candidate energy: the ticks it reaches back to may hold a shift). Once a gear has
// min_evidence_s of clean ticks, its f_n is the best candidate's (refined by a parabola in
// log f), if that correlation reaches min_correlation and beats "none" by
// min_correlation_gain; else the gear has no mode applied. Damping enters the in-band gain
// only to second order; zeta is fixed.
//
// Correction: hub_force_n() runs the reported force through the current gear's identified
// mode (a pass-through until it is). The filter's delay (2 zeta / w_n) is then the lag
// estimator's to find.
//
// Pure; not thread-safe; allocates only in the constructor.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "vmass/core/second_order_section.hpp"

namespace vmass {

struct DrivelineModeParams {
  bool enabled = true;
  double min_hz = 0.9;
  double max_hz = 12.0;
  int candidates = 24;  ///< on the log grid, besides "none"
  double damping_ratio = 0.15;
  double band_low_hz = 0.8;
  double band_high_hz = 8.0;
  double max_lag_s = 0.15;
  double min_evidence_s = 10.0;  ///< of clean ticks in the gear, s
  double min_correlation = 0.8;
  double min_correlation_gain = 0.02;  ///< over "none"

  std::string validate() const;
};

class DrivelineMode {
 public:
  static constexpr int kMaxGears = 16;

  DrivelineMode(const DrivelineModeParams& params, double tick_rate_hz);

  /// One tick: the reported (driveline) force, N, a_x, m/s^2, the engaged gear (0: none or
  /// unknown; 1 for a car without gears) and whether the tick is clean (no brake, the gear
  /// engaged and locked, moving). Identification only; call before hub_force_n().
  void observe(double force_n, double accel_x_mps2, int gear, bool clean);
  /// The force at the hub: the reported force_n through the gear's identified mode (force_n
  /// itself until it is identified, or for gear 0). Call on every tick after observe().
  double hub_force_n(double force_n, int gear);
  /// A hole in the data: the filters start again; what was identified stays.
  void restart();
  /// Forget everything (another vehicle).
  void reset();

  /// The gear's identified mode frequency, Hz; 0 when none is identified.
  double mode_hz(int gear) const;

 private:
  struct GearEvidence {
    long ticks = 0;
    double s_aa = 0.0;
    std::vector<double> s_xa;  ///< [candidate][lag]
    std::vector<double> s_xx;  ///< [candidate][lag]
    double mode_hz = 0.0;      ///< identified, 0: none
  };

  std::size_t candidate_count() const { return candidate_hz_.size() + 1; }  // + "none"
  /// Lags 0, lag_step_, ..., max_lag_ ticks.
  std::size_t lag_count() const { return static_cast<std::size_t>(max_lag_ / lag_step_) + 1; }
  void identify(GearEvidence& g);

  DrivelineModeParams params_;
  double rate_hz_;
  int max_lag_;
  int lag_step_;
  std::vector<double> candidate_hz_;
  std::vector<SecondOrderSection> candidate_modes_;  ///< on the band-passed force
  SecondOrderSection force_high_, force_low_, accel_high_, accel_low_;
  std::vector<double> history_;   ///< [lag slot][candidate]: the candidates' recent outputs
  std::vector<double> best_fit_;  ///< identify()'s scratch: each candidate's best correlation
  int head_ = 0;
  long primed_ = 0;
  std::array<GearEvidence, kMaxGears + 1> gears_;
  SecondOrderSection applied_;  ///< the current gear's mode, on the reported force
  double applied_hz_ = 0.0;
  bool applied_primed_ = false;
};

}  // namespace vmass

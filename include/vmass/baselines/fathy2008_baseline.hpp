// Fathy2008Baseline ("fathy2008"): H. K. Fathy, D. Kang, J. L. Stein, "Online vehicle mass
// estimation using recursive least squares and supervisory data extraction", Proc. American
// Control Conference 2008, 1842-1848. The idea, from perturbation theory: over high-frequency
// manoeuvres inertial dynamics dominate the longitudinal motion, so the slowly varying resistive
// forces (grade, rolling resistance, aero) drop out of filtered data; a supervisor feeds the RLS
// only the events where that holds and the signal is strong.
//
// Implemented:
//   F        = T_wheel / r - m_rot a_x                 traction force net of the rotating parts
//   F_f, a_f = BP(F), BP(a_x): the same band-pass on both, a 2nd-order Butterworth high-pass
//              (high_pass_hz, removes the resistive forces) and a 2nd-order Butterworth low-pass
//              (low_pass_hz, removes sensor noise and vibration)
//   supervisor: brakes off, in gear and not shifting, straight (|LP(a_y)| below a bound),
//              rolling (speed above a bound), and a high-excitation event |a_f| >= threshold
//   RLS      y = F_f = M a_f, one parameter, no forgetting, started at the empty mass
//   bound    +/- k sigma_M, sigma_M^2 = s^2 / sum a_f^2, s^2 the residual variance of the
//            accepted samples, k = 3 as in the paper ("conservative mass error estimates, in the
//            3 sigma sense"); reported in ci_low_kg / ci_high_kg as published, so it is wider
//            than a 95 % interval under the method's own error model.
// a_x is the accelerometer (specific force): its g sin(grade) is slowly varying like the grade
// force in F, so both leave through the high-pass. Samples at every tick.
//
// Assumptions (the paper's filter orders, cut-offs and thresholds could not be checked against a
// public copy; each value is the plainest reading, none tuned on the suite's scenarios):
// - high-pass 0.5 Hz (resistances vary over seconds: grade over tens of metres, drag with speed),
//   low-pass 2 Hz (throttle and braking events live below it; vibration above), excitation
//   |a_f| >= 0.2 m/s^2 (ten times the accelerometer noise), |LP(a_y)| < 0.5 m/s^2, speed >= 2 m/s.
// - Brakes off only: the method needs no brake signal (minimal instrumentation) and so cannot use
//   braking; without a pressure signal brakes-off ticks are told by a positive torque.
// - The rotating-mass correction m_rot a_x is given the benefit of the doubt (a tractive force
//   computed from engine torque through the driveline usually nets out its inertia); with the
//   grade removed by the high-pass, a_f is the filtered dv/dt it multiplies.
// - Gear: when the gear input is valid, a change restarts the pipeline and neutral/reverse are
//   unusable; without it shifts cannot be seen.
// - Samples at the tick rate are correlated by the filters; the bound, computed as if they were
//   independent (as RLS does), is narrower than the real uncertainty at a high tick rate.
// Deliberately not done: no braking data, no grade or resistance estimate, no forgetting.
// Not thread-safe; no allocation after construction.
#pragma once

#include <string>

#include "vmass/baselines/high_pass_filter.hpp"
#include "vmass/baselines/mass_baseline.hpp"
#include "vmass/baselines/nominal_vehicle.hpp"
#include "vmass/baselines/tick_continuity.hpp"
#include "vmass/baselines/tick_inputs.hpp"
#include "vmass/core/low_pass_filter.hpp"

namespace vmass::baselines {

struct Fathy2008Params {
  double high_pass_hz = 0.5;
  double low_pass_hz = 2.0;
  double min_abs_filtered_accel_mps2 = 0.2;  ///< the high-excitation event
  double max_abs_accel_y_mps2 = 0.5;
  double min_speed_mps = 2.0;
  double noise_std_n = 50.0;       ///< weighs the starting value against the data
  double prior_mass_std_kg = 0.0;  ///< 0: the empty mass
  double interval_sigmas = 3.0;

  std::string validate() const;
};

class Fathy2008Baseline final : public MassBaseline {
 public:
  Fathy2008Baseline(const NominalVehicle& vehicle, double tick_rate_hz,
                    const Fathy2008Params& params = Fathy2008Params{});

  void step(const vmass::Sample& sample) override;
  BaselineEstimate estimate() const override;
  std::string_view name() const override { return "fathy2008"; }

 private:
  struct Tick {
    double force_n = 0.0;
    double accel_x_mps2 = 0.0;
    double accel_y_mps2 = 0.0;
    int gear = 0;
    bool has_gear = false;
  };
  /// The tick's inputs, or false when the supervisor cannot use it at all.
  bool read(const vmass::Sample& sample, Tick* tick) const;
  void restart();
  void update(double y, double phi);

  NominalVehicle vehicle_;
  Fathy2008Params params_;
  bool usable_;
  BrakeRule brake_rule_;
  TickContinuity continuity_;
  HighPassFilter force_high_, accel_high_;
  vmass::LowPassFilter force_low_, accel_low_, accel_y_low_;
  Tick previous_;
  bool has_previous_ = false;
  // Scalar RLS on M and the sums for the residual variance.
  double mass_kg_;
  double variance_kg2_;
  double noise_var_n2_;
  double sum_phi2_ = 0.0, sum_phi_y_ = 0.0, sum_y2_ = 0.0;
  long updates_ = 0;
};

}  // namespace vmass::baselines

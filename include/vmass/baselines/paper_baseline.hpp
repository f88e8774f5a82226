// PaperBaseline ("paper"): the longitudinal block of El Mrhasli, Monsuez & Mouton, "Effective
// Combination of Vertical, Longitudinal and Lateral Data for Vehicle Mass Estimation", alone and
// as published, with its recursive least squares.
//
// Implemented:
//   F        = C_wheel / r_wheel - P_brake K_brake                       eqs. (6), (7)
//   dF, da_x = F(t) - F(t - dt), a_x(t) - a_x(t - dt), dt = 0.2 s        eq. (5), no filter
//   gates    |a_y| < 0.2 m/s^2, |da_x| > 0.01 m/s^2, |dF| > 10 N         Table II
//   y = dF = M da_x + mu,  phi = [da_x, 1]                               eq. (13), C1
//   RLS (PaperRls): eqs. (14)-(16) with a measurement-noise term         see paper_rls.hpp
// a_x is the accelerometer (specific force) as in the paper; C_wheel is the wheel torque signal.
// A pair is formed at every tick with the tick dt before it (the paper's 100 Hz CAN data and
// dt = 0.2 s, its real-data value).
//
// Assumptions (the paper is silent; each is the plainest reading):
// - Started at theta0 = [empty mass, 0] (the paper starts at M_initial from the suspension
//   sensor; the baseline has no static block) with a wide prior: sigma_M = prior_mass_std_kg
//   (default: the empty mass itself), sigma_mu = 500 N, and a measurement noise of 100 N (the
//   paper gives no P0 or noise level; the noise level only sets how fast the prior is forgotten).
// - The lateral gate applies at both ends of the difference (a pair mixes both instants).
// - Eq. (7) holds "if the wheels are not locked": a pair is formed only while the car rolls at
//   min_rolling_speed_mps or more at both ends (at standstill the pressure holds a parked car and
//   is not a force on it).
// - No brake-pressure signal: only brakes-off ticks are used, told by a positive wheel torque
//   while rolling (tick_inputs.hpp); K_brake = 0 (unknown) makes braking ticks unusable.
// - A tick with an unusable input (invalid, non-finite, brakes unknown) or out of time is a hole:
//   the differencing restarts after it.
// Deliberately not done (the paper has none of it): no filter, no rotating-mass correction (the
// estimate is of M plus the rotating parts' equivalent mass), no innovation gate, no forgetting,
// no speed gate beyond eq. (7), no lateral block (the suite scores longitudinal baselines).
// Not thread-safe; no allocation after construction.
#pragma once

#include <string>

#include "vmass/baselines/mass_baseline.hpp"
#include "vmass/baselines/nominal_vehicle.hpp"
#include "vmass/baselines/paper_rls.hpp"
#include "vmass/baselines/tick_continuity.hpp"
#include "vmass/baselines/tick_inputs.hpp"
#include "vmass/baselines/tick_window.hpp"

namespace vmass::baselines {

struct PaperParams {
  double differencing_dt_s = 0.2;
  double max_abs_accel_y_mps2 = 0.2;         ///< Table II
  double min_abs_delta_accel_x_mps2 = 0.01;  ///< Table II
  double min_abs_delta_force_n = 10.0;       ///< Table II
  double min_rolling_speed_mps = 1.0;        ///< eq. (7): wheels not locked
  double noise_std_n = 100.0;                ///< RLS measurement noise
  double prior_mass_std_kg = 0.0;            ///< 0: the empty mass
  double prior_mu_std_n = 500.0;

  std::string validate() const;
};

class PaperBaseline final : public MassBaseline {
 public:
  PaperBaseline(const NominalVehicle& vehicle, double tick_rate_hz,
                const PaperParams& params = PaperParams{});

  void step(const vmass::Sample& sample) override;
  BaselineEstimate estimate() const override;
  std::string_view name() const override { return "paper"; }

  const PaperRls& rls() const { return rls_; }

 private:
  struct Record {
    vmass::TimeUs time_us = 0;
    double force_n = 0.0;
    double accel_x_mps2 = 0.0;
    double accel_y_mps2 = 0.0;
    double speed_mps = 0.0;
  };
  /// The tick's record, or false when an input is unusable.
  bool read(const vmass::Sample& sample, Record* record) const;
  bool passes_gates(const Record& now, const Record& then) const;

  NominalVehicle vehicle_;
  PaperParams params_;
  bool usable_;
  BrakeRule brake_rule_;
  TickContinuity continuity_;
  TickWindow<Record> window_;
  PaperRls rls_;
};

}  // namespace vmass::baselines

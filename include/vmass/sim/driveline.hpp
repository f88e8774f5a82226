// Driveline: from the torque the powertrain puts into the driveline (Powertrain::wheel_torque_nm)
// to the torque at the hubs that drives the car. The half shafts and the gearbox make a lightly
// damped torsional mode whose frequency rises with the gear (the reflected prime-mover inertia
// falls), and the actuation and the ECU's computation put a lag between the ECU's report and
// the torque that acts:
//
//   u(t)      = T_in(t - lag_s)                                              (driveline_lag)
//   T_hub''   = w_n^2 (u - T_hub) - 2 zeta w_n T_hub'                        (driveline_mode)
//   w_n(g)    = 2 pi f_1 (i_1 / i_g)^p,  p = ln(f_top / f_1) / ln(i_1 / i_top)
// so f(1) = mode_frequency_first_gear_hz and f(top) = mode_frequency_top_gear_hz (single-speed:
// the top-gear value). The mode has unit static gain: over long horizons T_hub = T_in, so the
// differenced model of the paper holds between slow changes and fails for fast ones (the
// reported torque LEADS the hub torque). Integrated with RK4 at the caller's step (1 kHz).
//
// Not thread-safe; allocates only in the constructor (the lag's delay line).
#pragma once

#include <string>
#include <vector>

#include "vmass/sim/powertrain.hpp"
#include "vmass/sim/realism.hpp"

namespace vmass::sim {

struct DrivelineParams {
  double mode_frequency_first_gear_hz = 3.0;
  double mode_frequency_top_gear_hz = 8.0;
  double mode_damping_ratio = 0.15;
  double lag_s = 0.02;

  std::string validate(const std::string& prefix) const;
};

class Driveline {
 public:
  /// step_s: the integration step the caller uses (the lag is a whole number of them).
  Driveline(const DrivelineParams& params, const PowertrainParams& powertrain, double step_s,
            Realism effects);

  /// Start at rest in equilibrium with the input torque_nm.
  void reset(double torque_nm);
  /// Advance one step with input torque_in_nm in gear (0: driveline open, the mode relaxes).
  double step(double torque_in_nm, int gear);

  double hub_torque_nm() const { return torque_nm_; }
  /// The mode's natural frequency in gear, Hz.
  double mode_frequency_hz(int gear) const;

 private:
  DrivelineParams p_;
  std::vector<double> gear_ratios_;
  double step_s_;
  bool mode_on_;
  std::vector<double> delay_;  ///< ring buffer of past inputs (the lag)
  std::size_t head_ = 0;
  double torque_nm_ = 0.0;
  double rate_nm_per_s_ = 0.0;
  int last_gear_ = 1;  ///< the mode keeps its frequency while the clutch is open
};

}  // namespace vmass::sim

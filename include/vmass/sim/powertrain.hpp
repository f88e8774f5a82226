// Powertrain: the simulated car's drive, a prime mover (engine or motor of a hybrid) driving the
// front wheels through an automated 6-speed gearbox, with torque-interrupting gear shifts.
//
//   T_wheel = T_pm * s(t) * i_g * i_f * eta                wheel torque as the ECU defines it
//   T_pm'   = (T_cmd - T_pm) / tau,  0 <= T_cmd <= min(T_max, P_max / omega_pm)
//   m_rot(g) = (J_w + eta J_pm (i_g i_f)^2) / r^2           equivalent rotating mass, per gear
//   m_rot(0) = J_w / r^2                                     clutch open (during a shift)
//
// T_wheel is the torque before the rotating parts are accelerated: the car obeys
// (M + m_rot) dv_x/dt = T_wheel / r - ... (see VehicleModel), which is why config.yaml carries
// m_rot per gear. A shift (about 0.3 s) ramps the torque down (s: 1 -> 0, old gear), opens the
// clutch (s = 0, gear signal 0, engine decoupled), then ramps it up in the new gear (s: 0 -> 1).
//
// Not thread-safe (it has state); no allocation after construction.
#pragma once

#include <string>
#include <vector>

namespace vmass::sim {

struct PowertrainParams {
  std::vector<double> gear_ratios = {3.50, 2.10, 1.40, 1.00, 0.80, 0.65};  ///< i_g, gear 1..N
  double final_drive_ratio = 4.0;                                          ///< i_f
  double efficiency = 0.92;      ///< eta, driveline, applied to torque
  double max_torque_nm = 320.0;  ///< prime mover
  double max_power_w = 110000.0;
  double prime_mover_inertia_kgm2 = 0.08;  ///< J_pm (rotor/crank, flywheel, clutch)
  double wheel_inertia_kgm2 = 3.6;         ///< J_w: four wheels, discs, half shafts
  double torque_time_constant_s = 0.08;    ///< tau
  double upshift_speed_radps = 314.159;    ///< 3000 rpm of the prime mover
  double downshift_speed_radps = 125.664;  ///< 1200 rpm
  double min_time_in_gear_s = 1.5;
  double shift_ramp_down_s = 0.10;
  double shift_open_s = 0.10;
  double shift_ramp_up_s = 0.10;

  std::string validate(const std::string& prefix) const;
  int gear_count() const { return static_cast<int>(gear_ratios.size()); }
};

/// Equivalent rotating mass J/r^2 in gear 1..N, or with the clutch open (gear 0), kg.
double rotating_mass_kg(const PowertrainParams& p, int gear, double wheel_radius_m);

class Powertrain {
 public:
  Powertrain(const PowertrainParams& params, double wheel_radius_m);

  /// Start at rest or cruising: the gear that suits the speed, no shift, torque torque_nm at the
  /// wheels (clamped to what is available).
  void reset(double speed_mps, double wheel_torque_nm);

  /// Advance by dt_s towards the wheel-torque demand (>= 0), shifting by prime-mover speed.
  void step(double dt_s, double wheel_torque_demand_nm, double speed_mps);

  double wheel_torque_nm() const;  ///< T_wheel as defined above
  int gear_signal() const;         ///< engaged gear, 0 while the clutch is open
  int selected_gear() const { return gear_; }
  bool shifting() const { return shift_time_s_ >= 0.0; }
  double rotating_mass_kg() const;  ///< current m_rot
  /// Largest wheel torque available at this speed in the current gear.
  double max_wheel_torque_nm(double speed_mps) const;

 private:
  double ratio(int gear) const;  ///< i_g * i_f
  double pm_speed_radps(int gear, double speed_mps) const;
  double torque_scale() const;  ///< s(t) of the shift
  int engaged_gear() const;     ///< gear the clutch connects, 0 when open

  PowertrainParams p_;
  double r_;
  int gear_ = 1;
  int target_gear_ = 1;
  double pm_torque_nm_ = 0.0;
  double time_in_gear_s_ = 0.0;
  double shift_time_s_ = -1.0;  ///< < 0: no shift in progress
};

}  // namespace vmass::sim

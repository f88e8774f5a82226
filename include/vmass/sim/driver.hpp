// Driver: the simulated driver (or speed/steering controller) that follows a scenario's
// references and produces the car's inputs.
//
// Speed: a PI controller with feed-forward on a piecewise-linear speed reference v_ref(t):
//   F_dem = m_nom (dv_ref/dt + k_p (v_ref - v)) + k_i m_nom int (v_ref - v) dt + F_res,nom(v)
//   F_dem > 0: wheel-torque demand F_dem r_w;  F_dem < -band: brake pressure (-F_dem - band)/K
//   with regeneration (regen_max_force_n > 0, above regen_min_speed_mps), a negative F_dem goes
//   to a negative torque demand first, down to -regen_max_force_n r_w, the rest to the brakes
//   v_ref = 0 and v < 0.5 m/s: hold the car with a fixed pressure, no torque.
// From hold_reached_speed_from_s on (if set), v_ref is the speed the car had then and the
// integrator starts again: a speed controller engaged at the current speed, as a truck driver
// sets the cruise after pulling up with the accelerator floored.
// The pressure builds through a first-order lag (hydraulics). Torque lag is in the Powertrain.
//
// Steering: the steering-wheel angle (ISO: positive left) is either an open-loop profile
// (piecewise-linear base plus sine windows for slaloms) or, for a CircleCourse, pure pursuit
// on a circle of known radius through the origin, tangent to +x, with an integral term on the
// radial error so that the car ends up on the circle whatever its understeer.
//
// Not thread-safe (the controller has state).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "vmass/sim/piecewise_linear.hpp"
#include "vmass/sim/vehicle_model.hpp"

namespace vmass::sim {

/// A sinusoidal steering-wheel input on [start_s, end_s], faded in and out over one quarter
/// period at each end.
struct SteeringSine {
  double start_s = 0.0;
  double end_s = 0.0;
  double amplitude_rad = 0.0;  ///< steering-wheel angle amplitude
  double frequency_hz = 0.0;
};

/// Follow a circle of radius_m: left (centre at (0, R)) or right (centre at (0, -R)).
struct CircleCourse {
  double radius_m = 80.0;
  bool left = true;
};

struct DriverProfile {
  PiecewiseLinear speed_mps{0.0};                 ///< over time, s
  PiecewiseLinear steering_wheel_angle_rad{0.0};  ///< over time, s (open loop)
  std::vector<SteeringSine> steering_sines;
  std::optional<CircleCourse> circle;               ///< closed loop; overrides the open loop
  std::optional<double> hold_reached_speed_from_s;  ///< then v_ref = the speed reached, held

  std::string validate() const;
};

struct DriverParams {
  double nominal_mass_kg = 1600.0;          ///< m_nom: the driver's feel for the car
  double speed_gain_per_s = 1.0;            ///< k_p
  double speed_integral_gain_per_s2 = 0.2;  ///< k_i
  double coast_band_n = 80.0;               ///< neither throttle nor brake inside [-band, 0]
  double hold_pressure_pa = 15.0e5;         ///< pressure that holds the car at rest
  double max_brake_pressure_pa = 100.0e5;
  double brake_time_constant_s = 0.06;
  double lookahead_min_m = 6.0;  ///< pure pursuit: max(min, time * v)
  double lookahead_time_s = 0.8;
  double radial_integral_gain_rad_per_m_s = 0.002;
  double steering_time_constant_s = 0.05;  ///< hands: lag on the closed-loop steering command
  double regen_max_force_n = 0.0;          ///< brake blending of an electric car (0: none)
  double regen_min_speed_mps = 1.5;

  std::string validate() const;
};

/// What the driver commands for the next integration step.
struct DriverCommand {
  double wheel_torque_demand_nm = 0.0;
  double brake_pressure_pa = 0.0;  ///< actual (lagged) master-cylinder pressure
  double steering_wheel_angle_rad = 0.0;
};

class Driver {
 public:
  /// vehicle: used for the nominal resistance feed-forward and the steering geometry.
  Driver(const DriverParams& params, const DriverProfile& profile, const TrueVehicle& vehicle);

  /// Set the controller states for a car starting in state s at time t_s (no integrator wind,
  /// holding pressure if standing).
  void reset(double t_s, const VehicleState& s);

  /// The command for [t_s, t_s + dt_s) given the car's current state.
  DriverCommand update(double t_s, double dt_s, const VehicleState& s);

 private:
  double open_loop_steering(double t_s) const;
  double circle_steering(double dt_s, const VehicleState& s);

  DriverParams p_;
  DriverProfile profile_;
  TrueVehicle vehicle_;
  double speed_integral_ = 0.0;
  double brake_pressure_pa_ = 0.0;
  double radial_integral_ = 0.0;
  double steering_rad_ = 0.0;
  std::optional<double> held_speed_mps_;  ///< latched at hold_reached_speed_from_s
};

}  // namespace vmass::sim

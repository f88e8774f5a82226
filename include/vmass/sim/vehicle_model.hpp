// VehicleModel: the simulated car's planar motion, richer than the estimator's model so that the
// estimator is tested honestly. A single-track (bicycle) body with per-wheel tyre forces
// (double-track loads), integrated with classical RK4 (the simulator steps it at 1 kHz).
//
// States: x, y, yaw psi, v_x, v_y, yaw rate r (body frame, ISO 8855: x forward, y left, z up,
// yaw positive to the left), distance s, relaxed slip angles alpha_f, alpha_r, lagged specific
// forces (load transfer), rear-right suspension compression z and its rate.
//
//   (M + m_rot (1 + k)) dv_x/dt = F_X + M r v_y - m_rot v_x dk/dt
//                        (the rotating parts turn with the driven wheels, at v_x (1 + k), k their
//                        longitudinal slip: VehicleInputs::driven_slip, 0 without wheel_speed)
//   M (dv_y/dt + r v_x)  = F_Y
//   I_z dr/dt            = l_f (F_xf sin delta + F_yf cos delta) - l_r F_yr
//   F_X = F_xf cos delta - F_yf sin delta + F_xr - F_drag - M g sin theta
//   F_Y = F_xf sin delta + F_yf cos delta + F_yr - M g cos theta sin phi
//   F_xf = T_wheel / r_w - s_b K_brake P - f_r F_zf,   F_xr = -(1 - s_b) K_brake P - f_r F_zr
//   F_drag = 0.5 rho C_d A v_x |v_x|,   F_y* = sum over the axle's wheels of the magic formula
//   sigma dalpha/dt = v (alpha_ss - alpha),  alpha_ss,f = atan((v_y + l_f r)/v_x) - delta,
//                                            alpha_ss,r = atan((v_y - l_r r)/v_x)
//   F_zf = (M g cos theta l_r - M h f_x)/l, F_zr = (M g cos theta l_f + M h f_x)/l, and each
//   axle's lateral transfer share * M h f_y / track moves load to the outer (right in a left
//   turn) wheel; f_x, f_y lag the specific forces by the body's pitch/roll time constant.
//   Specific force (what the IMU measures): f_x = dv_x/dt - r v_y + g sin theta,
//                                           f_y = dv_y/dt + r v_x + g cos theta sin phi.
//
// Standstill: the car stops when v_x reaches 0 (or creeps below 2 cm/s while the brakes or the
// grade hold it) and starts again only when the drive force beats gravity plus the brake force;
// it never reverses (an implicit hill-hold keeps it from rolling back). At rest v_x = v_y = r = 0
// exactly, so the accelerometer reads g sin theta.
//
// Realism effects (realism.hpp) the model applies when switched on:
//   speed_resistance  f_r = f0 + f2 v_x^2, and a driveline viscous loss c_v v_x at the driven axle
//   wind              F_drag uses the airspeed v_x + w_head; a side force 0.5 rho C_y A w_c |w_c|
//   abs_esc           total brake force at most 0.95 mu(s) (F_zf + F_zr) (the pressure keeps
//                     rising: the ABS); above |a_y| = 0.75 mu g the ESC brakes with
//                     0.5 M (|a_y| - 0.75 mu g), a force no pressure signal shows
//   road_roughness    speed-bump pulses on each axle (Road::bump_deceleration_mps2)
// VehicleInputs::brake_gain_scale carries brake fade; the hub torque comes from the Driveline.
//
// Not modelled: combined slip, steering compliance, the wheels' own spin dynamics (the wheel
// speed is v_x; the simulator derives a quasi-static longitudinal slip from the axle forces for
// the speed signal and for the driveline's inertia above).
//
// Const member functions are thread-safe; VehicleState is a value owned by the caller.
#pragma once

#include "vmass/sim/mass_properties.hpp"
#include "vmass/sim/realism.hpp"
#include "vmass/sim/road.hpp"
#include "vmass/sim/true_vehicle.hpp"

namespace vmass::sim {

struct VehicleState {
  double x_m = 0.0;
  double y_m = 0.0;
  double yaw_rad = 0.0;
  double vx_mps = 0.0;
  double vy_mps = 0.0;
  double yaw_rate_radps = 0.0;
  double distance_m = 0.0;
  double slip_front_rad = 0.0;  ///< ISO slip angle (positive: force to the right)
  double slip_rear_rad = 0.0;
  double load_accel_x_mps2 = 0.0;  ///< lagged specific force driving load transfer
  double load_accel_y_mps2 = 0.0;
  double susp_compression_m = 0.0;  ///< rear-right spring compression from free length
  double susp_velocity_mps = 0.0;
  bool stopped = true;
};

/// What acts on the car during one integration step (held constant over the step).
struct VehicleInputs {
  MassProperties mass;
  double wheel_torque_nm = 0.0;   ///< torque at the hubs (Driveline::hub_torque_nm)
  double rotating_mass_kg = 0.0;  ///< m_rot (Powertrain::rotating_mass_kg)
  /// The driven wheels' longitudinal slip kappa and its rate: the rotating parts turn with the
  /// driven wheels, at v (1 + kappa), so they take up m_rot (dv/dt (1 + kappa) + v dkappa/dt).
  double driven_slip = 0.0;
  double driven_slip_rate_per_s = 0.0;
  double brake_pressure_pa = 0.0;
  double road_wheel_angle_rad = 0.0;  ///< delta, positive steering left
  double brake_gain_scale = 1.0;      ///< brake fade (1: none)
  double wind_head_mps = 0.0;         ///< Wind::head_mps
  double wind_cross_mps = 0.0;        ///< Wind::cross_mps
};

/// Forces and accelerations at one state (for truth output and tests).
struct VehicleOutputs {
  double dvx_dt_mps2 = 0.0;
  double dvy_dt_mps2 = 0.0;
  double yaw_accel_radps2 = 0.0;
  double specific_force_x_mps2 = 0.0;
  double specific_force_y_mps2 = 0.0;
  double grade_rad = 0.0;
  double bank_rad = 0.0;
  double drive_force_n = 0.0;  ///< T_wheel / r_w
  double brake_force_n = 0.0;  ///< K_brake P as applied (0 at rest)
  double drag_force_n = 0.0;
  double rolling_resistance_n = 0.0;
  double front_axle_load_n = 0.0;
  double rear_axle_load_n = 0.0;
  double rear_right_load_n = 0.0;      ///< wheel load incl. unsprung weight
  double lateral_force_front_n = 0.0;  ///< F_yf, ISO sign (positive to the left)
  double lateral_force_rear_n = 0.0;
  double esc_brake_force_n = 0.0;  ///< ESC intervention (not in the brake pressure)
  bool abs_active = false;         ///< the brake force is friction-limited
  double bump_force_n = 0.0;       ///< speed-bump pulses
  double viscous_loss_n = 0.0;     ///< driveline viscous loss
  double side_wind_force_n = 0.0;
};

class VehicleModel {
 public:
  VehicleModel(const TrueVehicle& params, const Road& road, Realism effects = Realism::none());

  /// A state with the suspension and load transfer at rest: standing (speed 0) or driving
  /// straight at speed_mps, at the start of the road, heading along +x.
  VehicleState settled_state(const VehicleInputs& in, double speed_mps) const;

  /// One RK4 step of dt_s with the standstill logic above.
  void step(VehicleState& s, const VehicleInputs& in, double dt_s) const;

  /// Forces and accelerations at s.
  VehicleOutputs evaluate(const VehicleState& s, const VehicleInputs& in) const;

  const TrueVehicle& params() const { return p_; }
  const Road& road() const { return road_; }

 private:
  TrueVehicle p_;
  Road road_;
  Realism effects_;
};

}  // namespace vmass::sim

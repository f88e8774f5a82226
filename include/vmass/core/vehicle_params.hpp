// VehicleParams and SuspensionParams: the vehicle constants the estimator assumes.
//
// Geometry follows the paper: l (wheelbase), l_f (centre of gravity to front axle),
// l_r = l - l_f. The rear-right suspension curve generalises eq. (3):
//   F_rr(z) = c (z - z0) + k2 max(0, z - z_knee)^2          wheel force above the empty state
// with z the sensor reading, z0 the reading with the empty vehicle (so F_rr(z0) = 0 when
// z0 < z_knee). With k2 = 0 this is the paper's linear spring.
//
// Plain values; thread-safe to share read-only.
#pragma once

#include <cmath>
#include <limits>
#include <string>
#include <vector>

namespace vmass {

struct VehicleParams {
  double empty_mass_kg = 0.0;                        ///< M_idle
  double wheelbase_m = 0.0;                          ///< l
  double cg_to_front_axle_m = 0.0;                   ///< l_f
  double wheel_radius_m = 0.0;                       ///< r_wheel
  double brake_gain_n_per_pa = 0.0;                  ///< K_brake
  double steering_ratio = 0.0;                       ///< steering-wheel angle / road-wheel angle
  double cornering_stiffness_front_n_per_rad = 0.0;  ///< C_alpha_f, per axle
  double cornering_stiffness_rear_n_per_rad = 0.0;   ///< C_alpha_r, per axle
  double rotating_mass_kg = 0.0;                     ///< J / r^2, constant
  std::vector<double> rotating_mass_by_gear_kg;      ///< optional, index gear - 1
  double gravity_mps2 = 9.80665;
  // From the datasheet, optional (0 or infinity: unknown).
  double max_mass_kg = std::numeric_limits<double>::infinity();  ///< maximum permissible mass
  double drag_area_m2 = 0.0;                                     ///< C_d A
  double air_density_kg_per_m3 = 1.2;
  double rolling_resistance_coeff = 0.0;  ///< f_r
  /// Declared accuracy (bound of the relative error) of the wheel-torque signal's scale and of
  /// wheel_radius_m: only the mass scaled by them is observable from traction pairs. The
  /// defaults are typical (an ECU's torque signal within 5 %, a dynamic radius within 2 %); 0
  /// declares it exact. They widen the 95 % interval (Estimate::mass_model_std_kg).
  double wheel_torque_accuracy_fraction = 0.05;
  double wheel_radius_accuracy_fraction = 0.02;
  /// Body pitch per longitudinal acceleration (a kinematics-and-compliance value): a body-fixed
  /// accelerometer tilts with the body and reads changes of a_x (1 + g k) too large, 1.7 % per
  /// deg/g. Unknown on most cars: the default is typical of passenger cars, and the estimator's
  /// interval carries its uncertainty (pitch_gradient_std_deg_per_g).
  double pitch_gradient_deg_per_g = 1.0;
  double pitch_gradient_std_deg_per_g = 0.5;
  /// Relative uncertainty of rotating_mass_kg / rotating_mass_by_gear_kg (inertias from a
  /// datasheet are rarely better than this): pairs whose rotating-mass term is large (low
  /// gears, an unlocked converter) count less.
  double rotating_mass_accuracy_fraction = 0.3;
  /// The wheels are driven by electric motors: their negative (regenerative) torque is known as
  /// well as their drive torque. A combustion engine dragged in overrun is not (see
  /// LongitudinalParams::use_overrun).
  bool electric_drive = false;
  /// The driveline, for a car that reports engine torque only (not wheel torque):
  ///   C_wheel = T_engine i_gear i_final eta    (T_engine / eta when the engine is dragged)
  /// Empty gear_ratios or final_drive_ratio 0: unknown (wheel torque is then required).
  /// With a wheel torque on the bus (wheel_torque_input) the ratios only read an automatic's
  /// converter from the engine speed (its TCU reports a wheel torque through its own model of
  /// the converter: LongitudinalExtractor).
  std::vector<double> gear_ratios;  ///< index gear - 1
  double final_drive_ratio = 0.0;
  /// The bus's wheel torque is the torque input (can.inputs maps wheel_torque): set by the
  /// config loader from the mapping, not a key. False: the engine torque through the ratios
  /// where they are given.
  bool wheel_torque_input = false;
  double driveline_efficiency = 0.92;
  /// Above this relative difference between the engine speed and the wheel speed through the
  /// gear, a torque converter or clutch slips and the engine torque does not reach the wheels
  /// by the ratios: such ticks are not clean.
  double max_driveline_slip_fraction = 0.05;
  /// A car with engine torque and engine speed on its bus but no gear number and no ratios in
  /// the config: the overall ratio is derived, i = w_engine r / v, while the converter is locked
  /// or the clutch closed (OverallRatioTracker). The block then needs engine_torque and
  /// engine_speed, not the gear; gear_ratios and final_drive_ratio are not used.
  bool derive_overall_ratio = false;
  /// The gearbox has a torque converter (an automatic; false for a manual, automated manual or
  /// double clutch). A converter at its coupling point holds the ratio steady but off the
  /// gear's, so only ratios seen above any lock-up speed count as locked: the derived ratio's
  /// plateaus, and the speed signal's scale against the engine (SpeedSignalScale).
  bool torque_converter = true;
  /// The converter's map, for an engine torque or a wheel torque with the gear number and the
  /// engine speed (ConverterMap): the torque ratio TR = stall - (stall - 1) SR / coupling below
  /// the coupling point, 1 above it, of the speed ratio SR = turbine speed / engine speed. With it
  /// an unlocked converter's ticks are used (a truck's automatic pulls away and drives its first
  /// gears unlocked); stall 0: the map is unknown and an engine torque's ticks there are not
  /// clean, as any slipping driveline's.
  double torque_converter_stall_torque_ratio = 0.0;
  double torque_converter_coupling_speed_ratio = 0.0;
  /// Bound of the map's relative error in TR - 1 (a maker's curve against the converter in the
  /// car); what it moves the mass by is in the interval (PairTermSensitivity).
  double torque_converter_map_accuracy_fraction = 0.25;
  /// Share of the engine's rotating mass still turning with the wheels while the converter is
  /// unlocked (turbine and gearbox input): m_rot = m_rot(0) + share (m_rot(gear) - m_rot(0)).
  /// Not on datasheets; rotating_mass_accuracy_fraction carries its error.
  double torque_converter_turbine_inertia_share = 0.2;
  /// With derive_overall_ratio: the engine's inertia (crank, flywheel, converter), kg m^2; its
  /// share of the rotating mass is eta J i^2 / r^2 at the derived ratio. 0: unknown (only
  /// rotating_mass_kg, the wheels', is counted).
  double engine_inertia_kgm2 = 0.0;
  /// With derive_overall_ratio: the bound of driveline_efficiency's relative error. No gearbox
  /// data declares it; until the lumped scale is learnt (LearntScale) it widens the interval.
  double driveline_efficiency_accuracy_fraction = 0.03;

  double cg_to_rear_axle_m() const { return wheelbase_m - cg_to_front_axle_m; }
  /// The payload between empty and the maximum permissible mass; 0 when no maximum is known.
  double payload_capacity_kg() const {
    const double capacity_kg = max_mass_kg - empty_mass_kg;
    return std::isfinite(capacity_kg) && capacity_kg > 0.0 ? capacity_kg : 0.0;
  }
  /// Equivalent rotating mass for the engaged gear; the constant when the gear is unknown.
  double rotating_mass_for_gear(int gear, bool gear_valid) const;
  /// Gear ratios and the final drive are known: wheel torque can come from engine torque.
  bool knows_driveline() const { return final_drive_ratio > 0.0 && !gear_ratios.empty(); }
  /// i_gear i_final for a forward gear; 0 when the gear is not one of gear_ratios.
  double overall_ratio(int gear) const;
  /// Wheel torque from engine torque in a forward gear (see above); NaN when unknown.
  double wheel_torque_from_engine_nm(double engine_torque_nm, int gear) const;
  /// The converter's map is configured (torque_converter_stall_torque_ratio above 1).
  bool knows_converter_map() const { return torque_converter_stall_torque_ratio > 1.0; }
  std::string validate() const;
};

struct SuspensionParams {
  /// A rear(-right) deflection sensor is configured (the config has a suspension section).
  bool has_sensor = true;
  /// The rear axle is self-levelling (air suspension): the ride height carries no load, so the
  /// sensor gives no static mass and the estimator starts from the no-static prior.
  bool levelled = false;
  double stiffness_n_per_m = 0.0;                                       ///< c_Brr
  double empty_deflection_m = 0.0;                                      ///< z0
  double progressive_knee_m = std::numeric_limits<double>::infinity();  ///< z_knee
  double progressive_rate_n_per_m2 = 0.0;                               ///< k2
  double linear_range_kg = std::numeric_limits<double>::infinity();
  double calibrated_range_kg = std::numeric_limits<double>::infinity();

  /// Rear-right wheel force above the empty state for a sensor reading z, N.
  double wheel_force_n(double deflection_m) const;
  bool is_progressive() const { return progressive_rate_n_per_m2 > 0.0; }
  /// Eq. (3) applies: a sensor whose reading carries the load.
  bool carries_load() const { return has_sensor && !levelled; }
  std::string validate() const;
};

}  // namespace vmass

// TrueVehicle: the TRUE parameters of a simulated car. The defaults are the demo car of the named
// scenarios (a front-wheel-drive hybrid SUV of about 1.5 t empty); the vehicle population
// (population.hpp) draws others. The config.yaml that vmass-sim writes is derived from these (see
// config_writer.hpp and datasheet.hpp for what the engineer knows and with which errors).
//
// The groups below the demo car's values are the realism effects' parameters (realism.hpp):
// they act only when the simulation switches their effect on.
//
// Plain value type; thread-safe to copy and read.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

#include "vmass/sim/driveline.hpp"
#include "vmass/sim/imu_model.hpp"
#include "vmass/sim/mass_properties.hpp"
#include "vmass/sim/powertrain.hpp"
#include "vmass/sim/suspension.hpp"
#include "vmass/sim/tyre.hpp"

namespace vmass::sim {

enum class DrivenAxle : std::uint8_t { kFront = 0, kRear, kAll };
std::string_view driven_axle_name(DrivenAxle a);
/// The share of the drive force on the front axle: 1, 0, or 0.5 on an all-wheel drive.
double front_drive_share(DrivenAxle a);

/// Brake pressure sensor and disc temperature (brake_sensor, brake_fade).
///   K_eff = K (1 - fade_max (clamp((T - T_start) / (T_full - T_start), 0, 1)))
///   C T' = F_brake v - C (T - T_ambient) / cooling_time_s
struct BrakeParams {
  double pressure_offset_pa = 0.0;  ///< the sensor reads P + this
  double heat_capacity_j_per_k = 12000.0;
  double cooling_time_s = 300.0;
  double ambient_c = 20.0;
  double fade_start_c = 250.0;
  double fade_full_c = 550.0;
  double fade_max_fraction = 0.25;

  std::string validate(const std::string& prefix) const;
  /// Brake gain scale at disc temperature temperature_c.
  double gain_scale(double temperature_c) const;
};

/// The vehicle-speed signal (wheel_speed): the ESC's mean of the four wheel speeds, each
///   v_wheel = v (1 + radius_error) (1 + kappa),  kappa = F_x,wheel / (slip_stiffness F_z,wheel)
/// and, on some cars, only the instrument cluster's display speed, which over-reads.
struct WheelSpeedParams {
  double radius_error_fraction = 0.0;  ///< the ESC's assumed radius against the true one
  double slip_stiffness = 15.0;        ///< C_kappa / F_z, per unit slip
  double display_overread_fraction = 0.03;
  double display_offset_mps = 0.3;

  std::string validate(const std::string& prefix) const;
};

struct TrueVehicle {
  /// Empty car (the M_idle of eq. 3): 1500 kg, l_f 1.20 m, CG 0.55 m high.
  MassProperties empty{1500.0, 1.20, 0.0, 0.55, 2400.0};
  double wheelbase_m = 2.70;            ///< l
  double track_m = 1.55;                ///< same front and rear
  double wheel_radius_m = 0.31;         ///< dynamic rolling radius
  double steering_ratio = 15.5;         ///< steering-wheel angle / road-wheel angle
  double brake_gain_n_per_pa = 0.0033;  ///< K_brake: total brake force per master-cyl. pressure
  double brake_front_share = 0.70;
  double drag_area_m2 = 0.75;  ///< C_d A
  double air_density_kg_per_m3 = 1.2;
  double rolling_resistance_coeff = 0.011;
  double gravity_mps2 = 9.80665;
  double roll_stiffness_front_share = 0.55;  ///< share of lateral load transfer on the front axle
  double load_transfer_time_constant_s = 0.08;  ///< body pitch/roll lag of the load transfer
  TyreParams front_tyre{18.0, 4000.0, 0.8, 1.0, 1.3, -0.3, 0.35};
  TyreParams rear_tyre{24.0, 4000.0, 0.8, 1.0, 1.3, -0.3, 0.35};
  PowertrainParams powertrain;
  SuspensionParams rear_right_suspension;

  // Realism parameters (act only when their effect is on).
  DrivenAxle driven_axle = DrivenAxle::kFront;
  DrivelineParams driveline;                              ///< driveline_mode, driveline_lag
  ImuParams imu;                                          ///< imu_*, body_pitch_roll
  double rolling_resistance_speed_coeff_s2_per_m2 = 0.0;  ///< f2: f_r = f0 + f2 v^2
  double driveline_viscous_n_per_mps = 0.0;               ///< loss at the wheels, c_v v
  double side_force_area_m2 = 0.0;  ///< C_y A_side: cross-wind side force 0.5 rho C_y A w^2
  BrakeParams brakes;
  WheelSpeedParams wheel_speed;
  /// Air suspension or self-levelling on the rear axle: the ride height returns to its nominal
  /// value after a load change, so the deflection carries no load information.
  bool rear_levelling = false;
  double levelling_time_constant_s = 8.0;

  /// "" or a message naming the key and the violated bound.
  std::string validate() const;
};

/// Static vertical loads of the car standing on level ground, N.
struct StaticLoads {
  double front_axle_n = 0.0;
  double rear_axle_n = 0.0;
  double front_left_n = 0.0;
  double front_right_n = 0.0;
  double rear_left_n = 0.0;
  double rear_right_n = 0.0;
};
StaticLoads static_loads(const TrueVehicle& v, const MassProperties& m);

/// Small-slip cornering stiffness of each axle at the static loads of m, N/rad (what the
/// estimator's C_alpha_f, C_alpha_r stand for).
struct AxleCorneringStiffness {
  double front_n_per_rad = 0.0;
  double rear_n_per_rad = 0.0;
};
AxleCorneringStiffness static_cornering_stiffness(const TrueVehicle& v, const MassProperties& m);

}  // namespace vmass::sim

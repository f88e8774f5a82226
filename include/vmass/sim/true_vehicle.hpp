// TrueVehicle: the TRUE parameters of the simulated car (a front-wheel-drive hybrid SUV of
// about 1.5 t empty). The config.yaml that vmass-sim writes is derived from these (see
// config_writer.hpp for which values it copies exactly and which carry a calibration error).
//
// Plain value type; thread-safe to copy and read.
#pragma once

#include <string>

#include "vmass/sim/mass_properties.hpp"
#include "vmass/sim/powertrain.hpp"
#include "vmass/sim/suspension.hpp"
#include "vmass/sim/tyre.hpp"

namespace vmass::sim {

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

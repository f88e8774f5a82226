// VehicleClass: the classes of the vehicle population (city car ... rigid heavy truck) and the
// ranges each class's vehicles are drawn from, every range with its source. Those ranges (the
// table in vehicle_class_table.cpp) and population.cpp's draw rules ARE the population's
// definition: docs/accuracy.md prints a hash of population_definition_text(), so any change to a
// range shows there (and its commit says why).
//
// Sources cited by key (population_sources() has the full references):
//   [TA]   EU type-approval / manufacturer datasheets of the class's example vehicles (kerb mass,
//          payload, wheelbase, track, power, tyre size, gear ratios)
//   [GIL]  T. D. Gillespie, Fundamentals of Vehicle Dynamics, SAE, 1992 (CG heights, weight
//          distribution, rolling resistance, road loads, braking)
//   [WONG] J. Y. Wong, Theory of Ground Vehicles, 4th ed., Wiley, 2008 (rolling resistance of car
//          and truck tyres, aerodynamic drag areas, truck driveline losses)
//   [HUCHO] W.-H. Hucho (ed.), Aerodynamics of Road Vehicles, SAE, 1998 (C_d A by body type)
//   [PAC]  H. B. Pacejka, Tyre and Vehicle Dynamics, 3rd ed., 2012 (cornering and slip stiffness
//          per load, relaxation length)
//   [RCVD] W. F. and D. L. Milliken, Race Car Vehicle Dynamics, SAE, 1995 (roll and pitch
//          gradients of passenger cars)
//   [CRO]  D. Crolla, B. Mashadi, Vehicle Powertrain Systems, Wiley, 2012, ch. 6 (driveline
//          shuffle modes, lightly damped, 2-10 Hz; torque converter characteristics)
//   [J2452] SAE J2452, Stepwise coastdown methodology for measuring tire rolling resistance
//          (f = f0 + f2 v^2 form)
//   [R39]  UN ECE Regulation 39 (speedometer: indicated speed never below true, at most
//          +10 % + 4 km/h)
//   [R48]  UN ECE Regulation 48 (automatic headlamp levelling for high-output lamps: ride-height
//          sensors, often on the rear axle only)
//   [ISO8608] ISO 8608, road surface profiles (roughness classes A-D)
//   [LIMP] R. Limpert, Brake Design and Safety, 3rd ed., SAE, 2011 (fade above ~300 C)
//   [ESC]  datasheets of ESC inertial sensor clusters (accelerometer noise, bandwidth, bias)
// Where a range is our own engineering judgement it says [ours] and why.
//
// Pure data and functions; thread-safe.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "vmass/sim/powertrain.hpp"
#include "vmass/sim/true_vehicle.hpp"

namespace vmass::sim {

enum class VehicleClass : std::uint8_t {
  kCityCar = 0,
  kCompact,
  kSaloon,
  kSuv,
  kVan,
  kPickup,
  kHeavyTruck,
  kCount
};
constexpr int kVehicleClassCount = static_cast<int>(VehicleClass::kCount);

std::string_view vehicle_class_name(VehicleClass c);  ///< "city_car", ...
std::optional<VehicleClass> parse_vehicle_class(std::string_view name);

/// A uniform range [low, high] and where it comes from.
struct Range {
  double low = 0.0;
  double high = 0.0;
  const char* source = "";
};

template <typename T>
struct Weighted {
  T value;
  double weight;
};

struct ClassDefinition {
  VehicleClass id = VehicleClass::kCompact;
  const char* examples = "";  ///< example vehicles whose datasheets the ranges follow
  Range empty_mass_kg;        ///< kerb mass (combustion variants)
  Range electric_extra_mass_fraction;
  Range payload_capacity_kg;  ///< maximum permissible mass - kerb mass
  Range wheelbase_m;
  Range track_m;
  Range front_weight_share;  ///< empty
  Range cg_height_m;         ///< empty
  Range drag_area_m2;
  Range rolling_f0;
  Range rolling_f2_s2_per_m2;
  Range driveline_viscous_n_per_mps;
  Range wheel_radius_m;
  Range power_kw;
  Range wheel_inertia_kgm2;   ///< all wheels, discs, shafts
  Range engine_inertia_kgm2;  ///< crank, flywheel (or rotor)
  Range steering_ratio;
  Range cornering_per_load_front;  ///< C_alpha / F_z at the reference load, 1/rad
  Range cornering_per_load_rear;
  double tyre_reference_load_n = 4000.0;
  Range rear_wheel_rate_n_per_m;  ///< rear suspension wheel rate
  Range roll_gradient_deg_per_g;
  Range pitch_gradient_deg_per_g;
  Range mode_first_gear_hz;
  Range mode_top_gear_hz;
  Range vibration_rms_mps2;       ///< IMU vibration at 30 m/s, smooth road
  Range brake_full_pressure_bar;  ///< master-cylinder (or air) pressure for 1 g at GVW
  std::vector<Weighted<Transmission>> transmissions;
  std::vector<Weighted<DrivenAxle>> driven_axles;
  double p_deflection_sensor = 0.5;   ///< a rear ride-height sensor on the bus
  double p_brake_pressure = 0.9;      ///< a master-cylinder pressure signal on the bus
  double p_engine_torque_only = 0.1;  ///< combustion: only engine torque, gear and engine speed
  double p_levelling = 0.0;           ///< air suspension / self-levelling rear axle
  double p_display_speed_only = 0.1;  ///< the only speed signal is the cluster's
  double p_no_lateral = 0.03;         ///< no a_y / yaw rate / steering on the bus mapped
};

/// The seven classes, in VehicleClass order.
const std::vector<ClassDefinition>& vehicle_classes();
const ClassDefinition& class_definition(VehicleClass c);

/// Ranges shared by every class (IMU, driveline lag, converter, ...), with their sources.
struct CommonRanges {
  Range driveline_lag_s;
  Range mode_damping_ratio;
  Range torque_time_constant_s;
  Range tc_stall_torque_ratio;
  Range tc_coupling_speed_ratio;
  Range tc_lockup_speed_mps;
  Range tc_model_error;
  Range creep_force_per_weight;
  Range drag_report_error;
  Range accessory_power_w;
  Range regen_max_decel_g;
  Range imu_filter_cutoff_hz;
  Range imu_bias_mps2;
  Range imu_drift_mps2_per_sqrt_s;
  Range imu_noise_std_mps2;
  Range imu_vibration_frequency_hz;
  Range imu_misalignment_deg;
  Range imu_lever_forward_m;
  Range imu_lever_left_m;
  Range speed_radius_error_fraction;
  Range display_overread_fraction;
  Range brake_pressure_offset_bar;
  Range brake_fade_max_fraction;
  Range empty_mass_deviation_fraction;  ///< true kerb vs datasheet (fuel, options)
  Range ecu_latency_s;
};
const CommonRanges& common_ranges();

/// The full references behind the [KEY]s.
std::string population_sources();
/// Every class and common range and probability, one per line, in a fixed format: the text
/// whose hash docs/accuracy.md prints.
std::string population_definition_text();
/// FNV-1a 64 of population_definition_text(), as 16 hex digits.
std::string population_definition_hash();

}  // namespace vmass::sim

// Population: vehicles drawn from the classes of vehicle_class.hpp, deterministically per
// (class, vehicle seed). A DrawnVehicle holds
//   - the TRUE vehicle (every realism effect's parameters filled in),
//   - what is on its CAN bus (VehicleSensors: a deflection sensor or not, brake pressure or not,
//     wheel or only engine torque, which speed) and how its DBC writes it (CanConventions),
//   - what its engineer knows and how wrong it is (KnowledgeErrors), for the two kinds of
//     knowledge the accuracy suite scores apart:
//       known scale      the torque signal's scale and the rolling radius are right; cornering
//                        stiffness +-20 %, brake gain +-10 %, rotating mass +-30 %, suspension
//                        stiffness +-5 %, C_d A +-10 %, rolling coefficient +-25 %
//       datasheet scale  the same, and the ECU's torque reads +-5 % off, the configured rolling
//                        radius +-2 %, both with the accuracy the engineer declares
// The population of N vehicles cycles through the classes (vehicle i: class i mod 7, seed
// first_seed + i). The development set starts at seed 1, the held-out set at
// kHeldOutFirstSeed: estimator work reports the held-out set apart and never tunes on it.
//
// Pure functions; thread-safe.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "vmass/sim/realism.hpp"
#include "vmass/sim/true_vehicle.hpp"
#include "vmass/sim/vehicle_class.hpp"

namespace vmass::sim {

constexpr std::uint64_t kDevelopmentFirstSeed = 1;
constexpr std::uint64_t kHeldOutFirstSeed = 100001;

enum class TorqueSignal : std::uint8_t {
  kWheelTorque = 0,  ///< one total wheel-torque signal
  kPerAxle,          ///< a wheel torque per axle (two motors, or engine + e-axle): the sum
  kEngineTorque,     ///< only engine torque, gear and engine speed
};
enum class SpeedSignal : std::uint8_t {
  kEsc = 0,  ///< the ESC's vehicle speed from the wheel speeds
  kDisplay,  ///< only the instrument cluster's displayed speed
};

/// What the vehicle puts on its bus that the estimator could use.
struct VehicleSensors {
  bool deflection = true;  ///< a rear(-right) ride-height sensor
  bool brake_pressure = true;
  TorqueSignal torque = TorqueSignal::kWheelTorque;
  SpeedSignal speed = SpeedSignal::kEsc;
  bool lateral = true;  ///< a_y, yaw rate and steering-wheel angle
  /// The gear number is on the bus and its ratios in the config; false: engine torque and speed
  /// only, the config derives the ratio (torque_signal_variant.hpp).
  bool gear_index = true;
};

/// How this vehicle's DBC writes its signals, and when its ECUs send them.
struct CanConventions {
  bool motorola = false;          ///< byte order of the vehicle's own messages
  bool extended_ids = false;      ///< 29-bit identifiers
  std::uint32_t id_base = 0x100;  ///< first message identifier
  bool accel_in_g = false;
  bool yaw_in_rad = false;
  bool yaw_positive_right = false;       ///< opposite to ISO 8855: the config's gain is -1
  bool steering_positive_right = false;  ///< likewise
  bool pressure_in_kpa = false;          ///< else bar
  bool deflection_muxed = false;         ///< level sensors share a multiplexed message
  // Cycle times and latencies (sensor filtering, gateway) of each message, s.
  double torque_period_s = 0.01, torque_latency_s = 0.01;
  double dynamics_period_s = 0.01, dynamics_latency_s = 0.02;  ///< a_x, a_y, yaw rate
  double speed_period_s = 0.01, speed_latency_s = 0.02;
  double brake_period_s = 0.01, brake_latency_s = 0.01;
  double steering_period_s = 0.01, steering_latency_s = 0.005;
  double level_period_s = 0.02, level_latency_s = 0.05;
  double display_period_s = 0.1, display_latency_s = 0.2;
};

/// Relative errors of what the engineer writes (value = true (1 + error)).
struct KnowledgeErrors {
  double cornering_front = 0.0, cornering_rear = 0.0;  ///< +-20 %
  double brake_gain = 0.0;                             ///< +-10 %
  double rotating_mass = 0.0;                          ///< +-30 %
  double suspension_stiffness = 0.0;                   ///< +-5 %
  double drag_area = 0.0;                              ///< +-10 %
  double rolling_coeff = 0.0;                          ///< +-25 %
  double cg_position_m = 0.0;                          ///< l_f from axle loads, +-1 % of l
  // datasheet scale only
  double torque_scale = 0.0;               ///< the ECU's torque reads (1 + this) x the true value
  double wheel_radius = 0.0;               ///< the configured radius is (1 + this) x the true one
  double declared_torque_accuracy = 0.05;  ///< what the engineer declares (bounds)
  double declared_radius_accuracy = 0.02;
};

struct DrawnVehicle {
  std::string id;  ///< "<class>-<seed>", e.g. "suv-7"
  VehicleClass vehicle_class = VehicleClass::kCompact;
  std::uint64_t seed = 0;
  TrueVehicle vehicle;  ///< truth; its empty mass is the datasheet's (see below)
  /// True kerb mass minus the datasheet's (fuel, options): added at the empty CG when the
  /// mass_uncertainty effect is on.
  double empty_mass_deviation_kg = 0.0;
  double payload_capacity_kg = 0.0;
  double max_mass_kg = 0.0;  ///< maximum permissible mass (datasheet)
  bool electric = false;
  bool tractor = false;  ///< pulls a semi-trailer: its payload sits on the fifth wheel
  VehicleSensors sensors;
  CanConventions can;
  KnowledgeErrors errors;

  /// The true vehicle with the effects that change the vehicle itself applied (its empty mass
  /// deviates from the datasheet's with mass_uncertainty).
  TrueVehicle true_vehicle(Realism realism) const;
  /// The seed of every random stream about this vehicle (its parameters, its bus, its life),
  /// each stream with an id of its own: one per (class, seed).
  std::uint64_t stream_seed() const {
    return seed * 16 + static_cast<std::uint64_t>(vehicle_class);
  }
};

DrawnVehicle draw_vehicle(VehicleClass vehicle_class, std::uint64_t vehicle_seed);
/// count vehicles, vehicle i of class i mod 7 with seed first_seed + i.
std::vector<DrawnVehicle> draw_population(int count, std::uint64_t first_seed);
/// Parses "<class>-<seed>" (the id) into a vehicle. Empty error on success.
bool parse_vehicle_id(const std::string& id, DrawnVehicle* out, std::string* error);
/// The engine speed is on the bus: beside an engine torque, and on every combustion heavy truck
/// whatever its torque signal (J1939's EEC1 carries it on every truck).
bool bus_has_engine_speed(const DrawnVehicle& v);
/// One line describing the vehicle (class, mass, powertrain, sensors), for logs and tables.
std::string describe_vehicle(const DrawnVehicle& v);
/// The draw rules that are code, not ranges (gear sets, probabilities of conventions, the
/// knowledge errors): part of the population's definition and its hash.
std::string population_rules_text();

}  // namespace vmass::sim

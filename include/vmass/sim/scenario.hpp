// Scenario: everything that defines one simulated drive (car, load over time, road, driver
// references, sensors, duration), and the registry of named scenarios vmass-sim offers.
//
//   paper_exp1   ECE-15-like urban cycle on a straight road with a slope profile, 1659 kg
//   paper_exp2   accelerating, braking, slaloms and constant-radius turns, 1659 kg
//   load_step    drive, stop, +250 kg while standing, drive again (1659 -> 1909 kg)
//   steady_turn  15 m/s on a left circle of 80 m radius (sign-convention test)
//
// Scenarios are plain data: tests build their own (flat road, grade at rest, ...) and run them
// through simulate(). Thread-safe to copy and read.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "vmass/sim/driver.hpp"
#include "vmass/sim/mass_properties.hpp"
#include "vmass/sim/road.hpp"
#include "vmass/sim/sensor_model.hpp"
#include "vmass/sim/true_vehicle.hpp"
#include "vmass/sim/wind.hpp"

namespace vmass::sim {

/// Items put into (or, with negative mass, taken out of) the car at start_s, ramped in linearly
/// over duration_s (people getting in). Positions as in LoadItem.
struct LoadChange {
  double start_s = 0.0;
  double duration_s = 2.0;
  std::vector<LoadItem> items;
};

struct Scenario {
  std::string name;
  std::string description;  ///< one line, for --list
  double duration_s = 60.0;
  double tick_rate_hz = 100.0;          ///< output (CAN) rate
  double integration_rate_hz = 1000.0;  ///< a multiple of tick_rate_hz
  double initial_speed_mps = 0.0;       ///< 0: start standing
  TrueVehicle vehicle;
  std::vector<LoadItem> initial_payload;  ///< on top of vehicle.empty
  std::vector<LoadChange> load_changes;
  Road road;
  WindParams wind;  ///< the wind effect
  DriverProfile driver;
  DriverParams driver_params;
  SensorSpec sensors;
  NoiseSet default_noise = NoiseSet::kEps1;

  /// Mass properties at time t_s (payload ramps included).
  MassProperties mass_at(double t_s) const;
  std::string validate() const;
};

/// Names of the registered scenarios, in --list order.
std::vector<std::string> scenario_names();
/// The registered scenario of that name, or nullopt.
std::optional<Scenario> find_scenario(std::string_view name);

}  // namespace vmass::sim

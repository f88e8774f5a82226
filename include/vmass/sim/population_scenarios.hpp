// Population scenarios: the drives the accuracy suite runs on every vehicle of the population,
// each built for the vehicle it runs on (a truck drives slower and turns gentler than a city
// car; lateral manoeuvres are given as lateral-acceleration targets and turned into that
// vehicle's steering) and deterministic per (vehicle, scenario, seed). Each scenario says what
// it stresses (population_scenario_description):
//
//   paper_exp1_eps1..3  the paper's experiment 1 (ECE-15-like urban cycle on slopes), with its
//                       wheel-force noise sets: resistive loads, slopes
//   paper_exp2_eps1..3  the paper's experiment 2 (accelerating, braking, slaloms, turns)
//   urban               stop-and-go: many short excitations, shifts, creep, a low-mu stop (ABS)
//   highway             steady high speed, lane changes: little excitation, aero, vibration
//   mountain            grades to 10 %, hairpins on banked curves, long braking (fade)
//   heavy_rear_load     payload near capacity in the boot / rear: eq. (3) over-reads, bump stop
//   windy               mean head or cross wind with gusts
//   rough_road          rough surface and speed bumps: vibration and force pulses
//   torque_bias         the ECU's torque reads 3 % high: what a biased torque does
//   load_change         drive, stop, load added at a stop, drive: re-initialisation
//   sensor_faults       a message missing, a frozen sensor, absurd values, bursts of unknown and
//                       malformed frames
// The seed draws the payload (people, luggage, cargo: how many and where) and the noise.
//
// Pure functions; thread-safe.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "vmass/sim/population.hpp"
#include "vmass/sim/scenario.hpp"
#include "vmass/sim/simulator.hpp"
#include "vmass/sim/vehicle_bus.hpp"

namespace vmass::sim {

/// One drive of one population vehicle: the physics, how it is simulated, and what the bus
/// adds (population_drive.hpp makes it a DriveSpec).
struct PopulationRun {
  std::string scenario;
  Scenario physics;              ///< its vehicle is the drawn vehicle's truth under the realism
  SimulationOptions simulation;  ///< seed, realism, the ECU trace the bus samples
  BusOptions bus;                ///< realism and seed set; eps, torque bias and faults per scenario
};

/// The car population's scenarios (the accuracy suite's default).
std::vector<std::string> population_scenario_names();
/// The truck population's: the car scenarios and the truck drives
///   truck_launch_flat                  accelerator floored from rest, shifting up (the torque
///                                      at its limit for 30-60 s), then a long cruise
///   truck_one_gear_flat/_grade/_rolling  one gear, never braking: floored from 40-55 km/h,
///                                      then a cruise; flat, 3 degrees, rolling hills
///   truck_coupling                     a tractor solo, a semi-trailer coupled at a stop
///                                      (+100-200 %), driven, uncoupled at a second stop
std::vector<std::string> truck_scenario_names();
/// One line: what the scenario stresses. Empty for an unknown name.
std::string population_scenario_description(std::string_view name);

/// Builds the run. "" or a message (unknown scenario, invalid result). `payload`, when given,
/// is the load at the start instead of the one the seed draws (a drive of a vehicle's lifetime:
/// what the last drive left, changed while parked); placed like the scenario's own.
std::string make_population_run(const DrawnVehicle& vehicle, std::string_view scenario,
                                std::uint64_t seed, Realism realism, PopulationRun* out,
                                const std::vector<LoadItem>* payload = nullptr);

}  // namespace vmass::sim

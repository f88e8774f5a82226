// A population vehicle's drives (vmass-sim --vehicle CLASS-SEED, vmass-suite): a population run
// (population_scenarios.hpp) on the drawn vehicle (population.hpp), with the vehicle's team: its
// own bus (vehicle_bus.hpp, the knowledge's torque scale on it) and the config its engineer
// writes from the datasheet (datasheet_config.hpp), as a team hands them over.
//
// Pure functions; thread-safe.
#pragma once

#include <memory>

#include "vmass/sim/datasheet_config.hpp"
#include "vmass/sim/drive.hpp"
#include "vmass/sim/population.hpp"
#include "vmass/sim/population_scenarios.hpp"

namespace vmass::sim {

/// The vehicle's team for the run under this knowledge (the suite hands one simulated drive to
/// a team per kind of knowledge).
std::shared_ptr<const VehicleTeam> population_team(const DrawnVehicle& vehicle,
                                                   const PopulationRun& run, Knowledge knowledge);

/// The run as a drive: its physics, its simulation options and population_team().
DriveSpec population_drive(const DrawnVehicle& vehicle, const PopulationRun& run,
                           Knowledge knowledge);

}  // namespace vmass::sim

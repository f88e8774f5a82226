// Files of a population drive, as a vehicle team would hand them over: DIR/vehicle.dbc (the
// vehicle's own DBC), DIR/drive.log (candump -l of its bus), DIR/config.yaml (written from the
// datasheet, datasheet_config.hpp), DIR/truth.csv (the hidden truth, the simulator's format)
// and DIR/samples.csv (the ECU signals at the ticks, noise-free: for debugging; the log is what
// the estimator sees).
//
// Functions writing files; thread-safe on distinct directories.
#pragma once

#include <string>
#include <vector>

#include "vmass/can/can_frame.hpp"
#include "vmass/sim/datasheet_config.hpp"
#include "vmass/sim/population_scenarios.hpp"
#include "vmass/sim/simulator.hpp"

namespace vmass::sim {

/// Simulates the run (with its ECU trace) and encodes its bus under the knowledge.
/// "" or a message.
std::string simulate_population_run(const DrawnVehicle& vehicle, const PopulationRun& run,
                                    Knowledge knowledge, SimulationResult* result,
                                    std::vector<can::CanFrame>* frames);

/// candump -l text of frames on interface can0.
std::string candump_text(const std::vector<can::CanFrame>& frames);

/// Writes the five files. "" or a message naming the file.
std::string write_population_files(const DrawnVehicle& vehicle, const PopulationRun& run,
                                   Knowledge knowledge, const SimulationResult& result,
                                   const std::vector<can::CanFrame>& frames,
                                   const std::string& dir);

}  // namespace vmass::sim

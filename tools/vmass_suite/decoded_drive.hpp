// One simulated drive as the product reads it: what the vehicle's team hands over (its bus
// under one kind of knowledge as candump text, its DBC and the config its engineer writes,
// vmass/sim/population_drive.hpp) put in a work directory
// and loaded with the real loaders (load_config, load_can_inputs), and the log decoded by the
// runtime's tick driver, exactly as `vmass-replay --log` does. A config the loader refuses (an
// input or section the estimator does not support yet) is reported as the run's error.
//
// Thread-safe for distinct work directories.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "vmass/config/config.hpp"
#include "vmass/core/sample.hpp"
#include "vmass/sim/drive.hpp"
#include "vmass/sim/simulator.hpp"

namespace vmass::suite {

struct DecodedDrive {
  std::string error;  ///< the bus, the config or the mapping was refused (unsupported)
  std::optional<Config> config;
  std::vector<Sample> samples;  ///< one per tick
  std::string log_text;         ///< the bus as candump -l lines
  std::string config_path;      ///< in the work directory, with vehicle.dbc beside it
};

struct DecodeOptions {
  std::string estimator_yaml;  ///< appended to the config (experiments)
  TimeUs time_offset_us = 0;   ///< added to every frame's time (a drive another day)
  bool keep_log_text = false;
};

DecodedDrive decode_drive(const sim::VehicleTeam& team, const sim::SimulationResult& result,
                          const DecodeOptions& options, const std::string& work_dir);

/// Writes a file; "" or "cannot write PATH".
std::string write_file(const std::string& path, const std::string& text);

/// The message without the work directory's prefix (the report names files by their names).
std::string without_dir(std::string message, const std::string& dir);

}  // namespace vmass::suite

// The demo car's drives (vmass-sim --scenario NAME): a named scenario (scenario.hpp) on the
// paper's car, with the demo team: the demo vehicle's bus (can_writer.hpp) and the config of a
// careful team that knows the car but for its suspension calibration (config_writer.hpp). The
// static ballast test also hands over ballast.csv and suspension_truth.yaml (static_ballast.hpp).
//
// Pure functions; thread-safe.
#pragma once

#include <optional>
#include <string_view>

#include "vmass/sim/drive.hpp"

namespace vmass::sim {

/// The named demo scenario (default options: seed 1, the scenario's noise set), or nullopt for
/// an unknown name.
std::optional<DriveSpec> demo_drive(std::string_view scenario);

}  // namespace vmass::sim

// check_torque_path: whether the longitudinal block can have its wheel torque from what
// `can.inputs` maps and what the `vehicle:` section knows (docs/signal-mapping.md):
//   wheel_torque mapped                                     the wheel torque
//   engine_torque + gear, vehicle.gear_ratios and final_drive_ratio     through the gear
//   engine_torque + engine_speed, vehicle.derive_overall_ratio: true    the derived ratio
// A mapping that gives none of them is an error at configuration time rather than a block that
// stays invalid forever. Configuration time only.
#pragma once

#include <string>

#include "vmass/config/config.hpp"
#include "vmass/signals/signal_mapping.hpp"

namespace vmass::signals {

/// "" when the block has a torque path (or is disabled); else "file:line: can.inputs...: what".
std::string check_torque_path(const Config& config, const SignalMapping& mapping);

}  // namespace vmass::signals

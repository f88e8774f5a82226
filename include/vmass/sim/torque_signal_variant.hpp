// TorqueSignalVariant: the same population vehicles with another torque signal on their bus,
// to compare the estimator's torque paths on the same drives (vmass-suite --torque-signal).
//   as_drawn            each vehicle's own (population.hpp: wheel torque, per axle, or engine)
//   engine_gear_index   every combustion vehicle: engine torque, engine speed and the gear
//                       number on its bus; its config has the gear ratios and the final drive
//   engine_speed_ratio  every combustion vehicle: engine torque and engine speed, no gear number
//                       (a selector-only gear signal is of no use, so none is mapped); its
//                       config has no ratios and derives the overall ratio
//                       (vehicle.derive_overall_ratio, OverallRatioTracker)
// Electric vehicles keep their wheel torque. The drive itself (the physics) does not change.
//
// Pure functions; thread-safe.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "vmass/sim/population.hpp"

namespace vmass::sim {

enum class TorqueSignalVariant : std::uint8_t {
  kAsDrawn = 0,
  kEngineGearIndex,
  kEngineSpeedRatio,
};

std::string_view torque_signal_variant_name(TorqueSignalVariant v);
/// The variant of a name above; empty for an unknown one.
std::optional<TorqueSignalVariant> parse_torque_signal_variant(std::string_view name);
/// "as_drawn, engine_gear_index, engine_speed_ratio" (for usage errors).
std::string torque_signal_variant_names();
/// The vehicle's sensors as the variant has them.
void apply_torque_signal_variant(TorqueSignalVariant variant, DrawnVehicle* vehicle);

}  // namespace vmass::sim

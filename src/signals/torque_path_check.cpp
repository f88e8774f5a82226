#include "vmass/signals/torque_path_check.hpp"

#include "vmass/config/yaml_reader.hpp"

namespace vmass::signals {

namespace {

/// What is missing for the engine torque to reach the wheels, "" when nothing is.
std::string engine_torque_gap(const VehicleParams& v, bool gear, bool engine_speed) {
  if (v.derive_overall_ratio) {
    return engine_speed ? ""
                        : "vehicle.derive_overall_ratio needs engine_speed mapped (the ratio is "
                          "engine speed x wheel radius / speed)";
  }
  if (v.knows_driveline()) {
    if (gear) return "";
    return "vehicle.gear_ratios need the gear mapped" +
           std::string(engine_speed ? "; or set vehicle.derive_overall_ratio: true to derive the "
                                      "ratio from engine_speed"
                                    : "");
  }
  return std::string(
             "no wheel_torque, and no vehicle.gear_ratios/final_drive_ratio to bring the "
             "engine torque to the wheels: ") +
         (engine_speed ? "set vehicle.derive_overall_ratio: true (the ratio from engine_speed)"
                       : "map engine_speed and set vehicle.derive_overall_ratio: true, or give "
                         "the ratios and map the gear");
}

}  // namespace

std::string check_torque_path(const Config& config, const SignalMapping& mapping) {
  if (!config.pipeline.estimator.longitudinal.enabled) return "";
  if (mapping.find(Input::kWheelTorque) != nullptr) return "";
  const bool engine_torque = mapping.find(Input::kEngineTorque) != nullptr;
  const bool engine_speed = mapping.find(Input::kEngineSpeed) != nullptr;
  const bool gear = mapping.find(Input::kGear) != nullptr;
  const VehicleParams& v = config.pipeline.vehicle;
  // Neither torque mapped: the block cannot run, as before this check (the inputs stay
  // invalid and the status says so); a wrong torque path is what is caught here.
  if (!engine_torque && !v.derive_overall_ratio) return "";
  std::string gap = engine_torque ? engine_torque_gap(v, gear, engine_speed)
                                  : "vehicle.derive_overall_ratio needs engine_torque mapped";
  if (gap.empty()) return "";
  try {
    YamlReader inputs(config.can["inputs"], config.file, "can.inputs");
    inputs.fail(engine_torque ? "engine_torque" : "engine_speed", gap);
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "";
}

}  // namespace vmass::signals

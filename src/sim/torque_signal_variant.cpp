#include "vmass/sim/torque_signal_variant.hpp"

#include <array>

namespace vmass::sim {

namespace {
constexpr std::array<TorqueSignalVariant, 3> kVariants = {TorqueSignalVariant::kAsDrawn,
                                                          TorqueSignalVariant::kEngineGearIndex,
                                                          TorqueSignalVariant::kEngineSpeedRatio};
}  // namespace

std::string_view torque_signal_variant_name(TorqueSignalVariant v) {
  switch (v) {
    case TorqueSignalVariant::kAsDrawn:
      return "as_drawn";
    case TorqueSignalVariant::kEngineGearIndex:
      return "engine_gear_index";
    case TorqueSignalVariant::kEngineSpeedRatio:
      return "engine_speed_ratio";
  }
  return "unknown";
}

std::optional<TorqueSignalVariant> parse_torque_signal_variant(std::string_view name) {
  for (TorqueSignalVariant v : kVariants) {
    if (name == torque_signal_variant_name(v)) return v;
  }
  return std::nullopt;
}

std::string torque_signal_variant_names() {
  std::string out;
  for (TorqueSignalVariant v : kVariants) {
    out += (out.empty() ? "" : ", ") + std::string(torque_signal_variant_name(v));
  }
  return out;
}

void apply_torque_signal_variant(TorqueSignalVariant variant, DrawnVehicle* vehicle) {
  if (variant == TorqueSignalVariant::kAsDrawn || vehicle->electric) return;
  vehicle->sensors.torque = TorqueSignal::kEngineTorque;
  vehicle->sensors.gear_index = variant == TorqueSignalVariant::kEngineGearIndex;
}

}  // namespace vmass::sim

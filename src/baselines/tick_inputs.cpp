#include "vmass/baselines/tick_inputs.hpp"

#include <algorithm>
#include <cmath>

namespace vmass::baselines {

std::optional<double> read_input(const vmass::Sample& sample, vmass::Input input) {
  if (!sample.has(input)) return std::nullopt;
  const double value = sample.value(input);
  if (!std::isfinite(value)) return std::nullopt;
  return value;
}

BrakeState brake_state(const vmass::Sample& sample, const BrakeRule& rule) {
  if (const auto pressure_pa = read_input(sample, vmass::Input::kBrakePressure)) {
    return *pressure_pa > rule.applied_above_pa ? BrakeState::kApplied : BrakeState::kOff;
  }
  const auto torque_nm = read_input(sample, vmass::Input::kWheelTorque);
  const auto speed_mps = read_input(sample, vmass::Input::kSpeed);
  if (torque_nm && speed_mps && *torque_nm > 0.0 && *speed_mps >= rule.min_speed_mps) {
    return BrakeState::kAssumedOff;
  }
  return BrakeState::kUnknown;
}

BrakeRule brake_rule_for(const NominalVehicle& vehicle, double min_speed_mps) {
  constexpr double kMinPressurePa = 2.0e4;
  constexpr double kWeightShare = 0.02;
  BrakeRule rule;
  rule.min_speed_mps = min_speed_mps;
  rule.applied_above_pa = kMinPressurePa;
  if (vehicle.brake_gain_n_per_pa > 0.0) {
    const double pa =
        kWeightShare * vehicle.empty_mass_kg * vehicle.gravity_mps2 / vehicle.brake_gain_n_per_pa;
    if (std::isfinite(pa)) rule.applied_above_pa = std::max(kMinPressurePa, pa);
  }
  return rule;
}

}  // namespace vmass::baselines

#include "vmass/baselines/tick_inputs.hpp"

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

}  // namespace vmass::baselines

// Reading a tick's inputs the way every baseline must: an input counts only when its validity bit
// is set and its value is finite; and whether the service brakes are on, which decides whether a
// tick's wheel force is known.
//
// Brake state from the master-cylinder pressure P when it is valid:
//   applied  when P > applied_above_pa   (the brake force K P is then present)
//   off      otherwise
// Some cars have no brake-pressure signal. Then a tick counts as "assumed off" only when the
// wheel torque is positive (the driver is on the throttle: production cars cut or override
// driving torque under braking) and the car is rolling at min_speed_mps or more (creeping
// against a held brake at standstill also shows a positive torque); otherwise the state is
// unknown and the tick is unusable for any method that needs the wheel force.
// Pure functions; thread-safe.
#pragma once

#include <optional>

#include "vmass/baselines/nominal_vehicle.hpp"
#include "vmass/core/sample.hpp"

namespace vmass::baselines {

/// The input's value when its validity bit is set and it is finite, else nullopt.
std::optional<double> read_input(const vmass::Sample& sample, vmass::Input input);

enum class BrakeState { kOff, kApplied, kAssumedOff, kUnknown };

struct BrakeRule {
  double applied_above_pa = 2.0e4;  ///< see brake_rule_for()
  double min_speed_mps = 1.0;       ///< for "assumed off" without a pressure signal
};

BrakeState brake_state(const vmass::Sample& sample, const BrakeRule& rule);

/// The rule for a vehicle: brakes count as applied above the pressure at which K_brake P reaches
/// 2 % of the empty car's weight (1.6 bar on a 1.5 t car, 0.07 bar with a truck's air brakes),
/// and never below 0.2 bar: above pressure sensors' zero offsets and noise, while the force
/// below it is small next to the traction changes the methods use.
BrakeRule brake_rule_for(const NominalVehicle& vehicle, double min_speed_mps);

/// True for kOff and kAssumedOff.
constexpr bool brakes_off(BrakeState state) {
  return state == BrakeState::kOff || state == BrakeState::kAssumedOff;
}

}  // namespace vmass::baselines

// ConverterMap: the engine torque through an unlocked torque converter, for a car whose bus has
// engine torque (or a wheel torque that holds the multiplication by the gearbox controller's
// model of it), engine speed and the gear number (an automatic's first gears, a truck pulling
// away), and whose config gives the ratios and the converter's map (vehicle.torque_converter_*).
//
//   SR = w_turbine / w_engine,    w_turbine = |v| / r i(gear)      the speed ratio
//   TR = stall - (stall - 1) SR / SR_c    for SR < SR_c;  1 at and above the coupling point
//   C_wheel = T_engine TR i eta
// The textbook's linear torque-ratio curve (a maker's map is near it); its error is declared as
// a bound on TR - 1 (torque_converter_map_accuracy_fraction), and the share of the estimate that
// rests on the multiplication is in the interval (PairTermSensitivity). Below the coupling point
// the engine's speed follows its torque (the stall curve), not the wheels, and only the turbine
// side of its inertia turns with them (torque_converter_turbine_inertia_share); at the coupling
// point the engine turns a fixed 1 / SR_c faster than the turbine and its whole inertia is the
// gear's rotating mass again.
//
// A tick is read through the map only while the engine turns faster than the turbine (driving)
// by more than the locked tolerance; an engine slower than the gear (overrun through the
// converter) or a speed ratio below kMinSpeedRatio (near stall, where the curve is least known)
// is a slipping driveline, not used.
//
// Pure; thread-safe (no state).
#pragma once

#include "vmass/core/vehicle_params.hpp"

namespace vmass {

/// How the engine's torque reaches the wheels on this tick.
enum class DrivelineCoupling {
  kLocked,     ///< engine speed within the slip tolerance of the gear's: TR 1
  kConverter,  ///< an unlocked converter driving, read through the map
  kSlipping,   ///< an open clutch, overrun through a converter, no map: not usable
};

struct ConverterReading {
  DrivelineCoupling coupling = DrivelineCoupling::kSlipping;
  double speed_ratio = 1.0;   ///< SR
  double torque_ratio = 1.0;  ///< TR (1 unless kConverter below the coupling point)
};

class ConverterMap {
 public:
  static constexpr double kMinSpeedRatio = 0.3;

  explicit ConverterMap(const VehicleParams& vehicle)
      : known_(vehicle.knows_converter_map()),
        stall_(vehicle.torque_converter_stall_torque_ratio),
        coupling_(vehicle.torque_converter_coupling_speed_ratio),
        locked_slip_(vehicle.max_driveline_slip_fraction),
        turbine_share_(vehicle.torque_converter_turbine_inertia_share) {}

  /// The coupling for the engine speed and the turbine speed the gear implies (both rad/s).
  ConverterReading read(double engine_speed_radps, double turbine_speed_radps) const;
  /// TR at the speed ratio sr by the configured map (1 without a map).
  double torque_ratio(double speed_ratio) const;
  /// m_rot below the coupling point, from the locked gear's m_rot and the wheels' alone (kg).
  double unlocked_rotating_mass_kg(double gear_kg, double wheels_kg) const {
    return wheels_kg + turbine_share_ * (gear_kg - wheels_kg);
  }

 private:
  bool known_;            ///< VehicleParams::knows_converter_map()
  double stall_;          ///< TR at SR 0
  double coupling_;       ///< SR_c
  double locked_slip_;    ///< max_driveline_slip_fraction
  double turbine_share_;  ///< torque_converter_turbine_inertia_share
};

}  // namespace vmass

// Datasheet config: the config.yaml a vehicle team writes for a population vehicle from its
// datasheets and its own calibration, never from the simulator's truth:
//   vehicle      kerb mass from the datasheet (the true empty mass differs with
//                mass_uncertainty); l_f of the EMPTY car from the datasheet's axle loads; the
//                small-slip cornering stiffness at the EMPTY axle loads; K_brake, m_rot, C_d A,
//                f_r with the vehicle's KnowledgeErrors (datasheet_errors); the maximum
//                permissible mass; in the datasheet-scale population also the rolling radius
//                off by its error and the declared accuracies of torque scale and radius
//   suspension   only with a deflection sensor: the calibrated stiffness (+-5 %), the empty
//                reading, the linear range; a levelled rear axle is declared as such
//   estimator    nothing: the loader's defaults are what the accuracy suite scores
//   can          the mapping of the vehicle's DBC (VehicleBus::can_config_yaml)
// Inputs and keys the estimator does not support yet (engine torque, brake switch, a levelled
// axle) are written as the engineer would write them: the loader rejects them, and the suite
// scores such vehicles "unsupported" with the loader's message.
//
// Pure functions; thread-safe.
#pragma once

#include <string>
#include <string_view>

#include "vmass/sim/population.hpp"

namespace vmass::sim {

enum class Knowledge : std::uint8_t {
  kKnownScale = 0,  ///< torque scale and rolling radius right
  kDatasheetScale,  ///< both off by the vehicle's errors, declared in the config
};
std::string_view knowledge_name(Knowledge k);

std::string datasheet_config_yaml(const DrawnVehicle& vehicle, Realism realism, Knowledge knowledge,
                                  const std::string& dbc_file);

/// The torque scale the vehicle's ECU reports with under this knowledge (1 in known scale).
double torque_report_scale(const DrawnVehicle& vehicle, Knowledge knowledge);

}  // namespace vmass::sim

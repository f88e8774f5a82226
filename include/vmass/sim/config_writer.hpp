// Config writer: the config.yaml that goes with a drive of the demo car (demo_drive.hpp), in the
// schema of docs/formats.md. It holds what a careful vehicle team would know about the car:
//
// exact (the paper assumes them known):
//   vehicle.empty_mass_kg, wheelbase_m, wheel_radius_m, brake_gain_n_per_pa, steering_ratio,
//   gravity_mps2; cg_to_front_axle_m = l_f of the car as loaded at the start of the scenario;
//   cornering_stiffness_{front,rear}_n_per_rad = small-slip slope of the simulated tyres summed
//   over the axle at the static wheel loads at the start (see tyre.hpp); rotating_mass_kg =
//   J_w / r^2 (clutch open) and rotating_mass_by_gear_kg = (J_w + eta J_pm (i_g i_f)^2) / r^2;
//   suspension.empty_deflection_m (sensor reading of the empty car standing level) and
//   progressive_knee_m (the bump stop, in sensor coordinates).
// with a calibration error (CalibrationErrors, documented in the file's header comment):
//   suspension.stiffness_n_per_m and progressive_rate_n_per_m2 are 3 % low; the sensor has also
//   drifted +0.2 mm since calibration (SensorSpec). linear_range_kg follows from the written
//   curve (added load at the centre of gravity that reaches the knee); calibrated_range_kg is the
//   ballast range of the calibration (800 kg).
// estimator: `type: bayes`, and tick_rate_hz when the scenario's differs from the default;
//   every other key is left at its default (nothing is tuned to the simulated car).
// The keys and their spelling come from the config's field tables (vmass/config/*_section.hpp).
// No `lcm:` section (defaults); the `can:` section is the demo vehicle's (can_writer.hpp).
//
// Stateless functions; thread-safe on distinct streams.
#pragma once

#include <ostream>
#include <string>
#include <vector>

#include "vmass/core/pipeline.hpp"
#include "vmass/sim/simulator.hpp"

namespace vmass::sim {

struct CalibrationErrors {
  double suspension_stiffness_scale = 0.97;  ///< written c and k2 = true * this
  double calibrated_range_kg = 800.0;        ///< ballast range of the calibration (8 x 100 kg)
};

/// What the team's config says about a car with true parameters `vehicle`, loaded as `loaded`.
PipelineParams make_config_params(const TrueVehicle& vehicle, const MassProperties& loaded,
                                  double tick_rate_hz, const CalibrationErrors& errors = {});

/// The YAML text; header_comment lines (without '#') go on top.
void write_config_yaml(std::ostream& os, const PipelineParams& params,
                       const std::vector<std::string>& header_comment);

/// The demo car's config.yaml for a simulation result, without its `can:` section (the demo
/// team, demo_drive.hpp, appends can_writer.hpp's).
std::string demo_config_yaml(const SimulationResult& result, const CalibrationErrors& errors = {});

}  // namespace vmass::sim

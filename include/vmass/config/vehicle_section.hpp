// The `vehicle:` section of the config (docs/formats.md): one field table that the loader reads
// and both simulator config writers write, so that the schema exists in one place.
//
// Configuration time only; not thread-safe (YAML::Emitter).
#pragma once

#include <array>

#include <yaml-cpp/yaml.h>

#include "vmass/config/field_table.hpp"
#include "vmass/config/yaml_reader.hpp"
#include "vmass/core/vehicle_params.hpp"

namespace vmass {

inline constexpr std::array<Field<VehicleParams>, 33> kVehicleFields{{
    {"empty_mass_kg", &VehicleParams::empty_mass_kg, true},
    {"wheelbase_m", &VehicleParams::wheelbase_m, true},
    {"cg_to_front_axle_m", &VehicleParams::cg_to_front_axle_m, true},
    {"wheel_radius_m", &VehicleParams::wheel_radius_m, true},
    {"brake_gain_n_per_pa", &VehicleParams::brake_gain_n_per_pa, true},
    {"steering_ratio", &VehicleParams::steering_ratio, true},
    {"cornering_stiffness_front_n_per_rad", &VehicleParams::cornering_stiffness_front_n_per_rad,
     true},
    {"cornering_stiffness_rear_n_per_rad", &VehicleParams::cornering_stiffness_rear_n_per_rad,
     true},
    {"rotating_mass_kg", &VehicleParams::rotating_mass_kg},
    {"rotating_mass_by_gear_kg", &VehicleParams::rotating_mass_by_gear_kg},
    {"gravity_mps2", &VehicleParams::gravity_mps2},
    {"max_mass_kg", &VehicleParams::max_mass_kg},
    {"drag_area_m2", &VehicleParams::drag_area_m2},
    {"air_density_kg_per_m3", &VehicleParams::air_density_kg_per_m3},
    {"rolling_resistance_coeff", &VehicleParams::rolling_resistance_coeff},
    {"wheel_torque_accuracy_fraction", &VehicleParams::wheel_torque_accuracy_fraction},
    {"wheel_radius_accuracy_fraction", &VehicleParams::wheel_radius_accuracy_fraction},
    {"pitch_gradient_deg_per_g", &VehicleParams::pitch_gradient_deg_per_g},
    {"pitch_gradient_std_deg_per_g", &VehicleParams::pitch_gradient_std_deg_per_g},
    {"rotating_mass_accuracy_fraction", &VehicleParams::rotating_mass_accuracy_fraction},
    {"electric_drive", &VehicleParams::electric_drive},
    {"gear_ratios", &VehicleParams::gear_ratios},
    {"final_drive_ratio", &VehicleParams::final_drive_ratio},
    {"driveline_efficiency", &VehicleParams::driveline_efficiency},
    {"max_driveline_slip_fraction", &VehicleParams::max_driveline_slip_fraction},
    {"derive_overall_ratio", &VehicleParams::derive_overall_ratio},
    {"torque_converter", &VehicleParams::torque_converter},
    {"engine_inertia_kgm2", &VehicleParams::engine_inertia_kgm2},
    {"driveline_efficiency_accuracy_fraction",
     &VehicleParams::driveline_efficiency_accuracy_fraction},
    {"torque_converter_stall_torque_ratio", &VehicleParams::torque_converter_stall_torque_ratio},
    {"torque_converter_coupling_speed_ratio",
     &VehicleParams::torque_converter_coupling_speed_ratio},
    {"torque_converter_map_accuracy_fraction",
     &VehicleParams::torque_converter_map_accuracy_fraction},
    {"torque_converter_turbine_inertia_share",
     &VehicleParams::torque_converter_turbine_inertia_share},
}};

/// Reads the section; unknown keys are errors. Throws ConfigError.
inline void read_vehicle_section(YamlReader r, VehicleParams* params) {
  read_fields(r, kVehicleFields, params);
  r.reject_unknown_keys();
}

/// Emits `vehicle` and its map (the table's order, with the comments) into an emitter that is
/// inside a map; the emitter's double precision applies.
inline void emit_vehicle_section(YAML::Emitter& out, const VehicleParams& params,
                                 const FieldComments& comments, FieldSelection which) {
  out << YAML::Key << "vehicle" << YAML::Value << YAML::BeginMap;
  emit_fields(out, kVehicleFields, params, comments, which);
  out << YAML::EndMap;
}

}  // namespace vmass

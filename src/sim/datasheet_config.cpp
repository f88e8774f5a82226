#include "vmass/sim/datasheet_config.hpp"

#include <sstream>

#include <yaml-cpp/yaml.h>

#include "vmass/config/suspension_section.hpp"
#include "vmass/config/vehicle_section.hpp"
#include "vmass/sim/powertrain.hpp"
#include "vmass/sim/suspension.hpp"
#include "vmass/sim/vehicle_bus.hpp"

namespace vmass::sim {

namespace {

/// Engine torque and engine speed without the gear number: no ratios (nor the per-gear masses
/// computed from them), the engine's inertia instead, the efficiency's accuracy declared as the
/// torque's is.
void derive_ratio(const TrueVehicle& v, double rotating_error_scale, double efficiency_accuracy,
                  VehicleParams* p) {
  p->gear_ratios.clear();
  p->final_drive_ratio = 0.0;
  p->rotating_mass_by_gear_kg.clear();
  p->derive_overall_ratio = true;
  p->engine_inertia_kgm2 = v.powertrain.prime_mover_inertia_kgm2 * rotating_error_scale;
  p->driveline_efficiency_accuracy_fraction = efficiency_accuracy;
  p->torque_converter = v.powertrain.has_torque_converter();  // the gearbox's kind is known
}

/// An automatic's converter map as its maker gives it: the curve the TCU's own model holds, off
/// the converter in the car by tc_model_error in TR - 1 when `errors`.
void converter_map(const PowertrainParams& pt, bool errors, VehicleParams* p) {
  const double map_error = errors ? pt.tc_model_error : 0.0;
  p->torque_converter_stall_torque_ratio =
      1.0 + (pt.tc_stall_torque_ratio - 1.0) * (1.0 + map_error);
  p->torque_converter_coupling_speed_ratio = pt.tc_coupling_speed_ratio;
}

/// The `vehicle:` values its engineer knows: the datasheet's, with its errors when `errors`.
VehicleParams datasheet_vehicle(const DrawnVehicle& d, bool errors, Knowledge k) {
  const TrueVehicle& v = d.vehicle;
  const KnowledgeErrors& e = d.errors;
  auto err = [&](double x) { return errors ? x : 0.0; };
  const AxleCorneringStiffness cs = static_cornering_stiffness(v, v.empty);
  VehicleParams p;
  p.empty_mass_kg = v.empty.mass_kg;
  p.max_mass_kg = d.max_mass_kg;
  p.wheelbase_m = v.wheelbase_m;
  p.cg_to_front_axle_m = v.empty.cg_x_m + err(e.cg_position_m);
  p.wheel_radius_m =
      v.wheel_radius_m * (1.0 + (k == Knowledge::kDatasheetScale ? e.wheel_radius : 0.0));
  p.brake_gain_n_per_pa = v.brake_gain_n_per_pa * (1.0 + err(e.brake_gain));
  p.steering_ratio = v.steering_ratio;
  p.cornering_stiffness_front_n_per_rad = cs.front_n_per_rad * (1.0 + err(e.cornering_front));
  p.cornering_stiffness_rear_n_per_rad = cs.rear_n_per_rad * (1.0 + err(e.cornering_rear));
  const double rot = 1.0 + err(e.rotating_mass);
  p.rotating_mass_kg = rotating_mass_kg(v.powertrain, 0, v.wheel_radius_m) * rot;
  for (int g = 1; g <= v.powertrain.gear_count(); ++g) {
    p.rotating_mass_by_gear_kg.push_back(rotating_mass_kg(v.powertrain, g, v.wheel_radius_m) * rot);
  }
  p.electric_drive = v.powertrain.transmission == Transmission::kElectric;
  p.drag_area_m2 = v.drag_area_m2 * (1.0 + err(e.drag_area));
  p.rolling_resistance_coeff = v.rolling_resistance_coeff * (1.0 + err(e.rolling_coeff));
  const bool declared = k == Knowledge::kDatasheetScale;
  p.wheel_torque_accuracy_fraction = declared ? e.declared_torque_accuracy : 0.0;
  p.wheel_radius_accuracy_fraction = declared ? e.declared_radius_accuracy : 0.0;
  // The gearbox's datasheet: for the engine torque's path, and for a wheel torque beside the
  // engine speed and the gear, to read an automatic's converter.
  const bool gearbox = d.sensors.torque == TorqueSignal::kEngineTorque ||
                       (bus_has_engine_speed(d) && d.sensors.gear_index);
  if (gearbox) {
    p.gear_ratios = v.powertrain.gear_ratios;
    p.final_drive_ratio = v.powertrain.final_drive_ratio;
    p.driveline_efficiency = v.powertrain.efficiency;
    p.torque_converter = v.powertrain.has_torque_converter();  // the gearbox's kind is known
    if (v.powertrain.has_torque_converter()) converter_map(v.powertrain, errors, &p);
  }
  if (d.sensors.torque == TorqueSignal::kEngineTorque && !d.sensors.gear_index) {
    derive_ratio(v, rot, declared ? e.declared_torque_accuracy : 0.0, &p);
  }
  return p;
}

/// The `suspension:` calibration (vmass-calibrate on ballast), with its error when `errors`.
vmass::SuspensionParams datasheet_suspension(const DrawnVehicle& d, bool errors) {
  const TrueVehicle& v = d.vehicle;
  const SuspensionParams& sp = v.rear_right_suspension;
  const StaticLoads empty = static_loads(v, v.empty);
  vmass::SuspensionParams p;
  p.empty_deflection_m =
      spring_compression(sp, empty.rear_right_n - sp.unsprung_mass_kg * v.gravity_mps2) -
      sp.sensor_reference_m;
  p.stiffness_n_per_m =
      sp.stiffness_n_per_m * (1.0 + (errors ? d.errors.suspension_stiffness : 0.0));
  const double knee = sp.knee_compression_m - sp.sensor_reference_m;
  // Eq. (3) inverted at the knee: the added load at the CG that reaches it.
  p.linear_range_kg = 2.0 * v.wheelbase_m * p.stiffness_n_per_m * (knee - p.empty_deflection_m) /
                      (v.empty.cg_x_m * v.gravity_mps2);
  p.calibrated_range_kg = d.payload_capacity_kg;
  return p;
}

void emit_suspension(YAML::Emitter& out, const DrawnVehicle& d, bool errors) {
  if (!d.sensors.deflection) return;
  if (d.vehicle.rear_levelling) {
    out << YAML::Key << "suspension" << YAML::Value << YAML::BeginMap << YAML::Key << "levelled"
        << YAML::Value << true << YAML::Comment("air suspension: the ride height carries no load")
        << YAML::EndMap;
    return;
  }
  emit_suspension_section(out, datasheet_suspension(d, errors),
                          {{"stiffness_n_per_m", "vmass-calibrate on ballast"}},
                          FieldSelection::kRequiredOrSet);
}

}  // namespace

std::string_view knowledge_name(Knowledge k) {
  return k == Knowledge::kKnownScale ? "known_scale" : "datasheet_scale";
}

double torque_report_scale(const DrawnVehicle& vehicle, Knowledge knowledge) {
  return knowledge == Knowledge::kDatasheetScale ? 1.0 + vehicle.errors.torque_scale : 1.0;
}

std::string datasheet_config_yaml(const DrawnVehicle& vehicle, Realism realism, Knowledge knowledge,
                                  const std::string& dbc_file) {
  const bool errors = realism.has(Effect::kDatasheetErrors);
  std::ostringstream os;
  os << "# vmass config for population vehicle " << vehicle.id << ", written by vmass-sim from\n"
     << "# what its engineer knows (" << knowledge_name(knowledge)
     << "): datasheet values, the suspension calibration, the DBC.\n"
     << "# " << describe_vehicle(vehicle) << "\n"
     << "# No estimator section: the estimator runs on its defaults.\n";
  // What is known and differs from the loader's defaults: the defaults are what the loader
  // would take anyway, and a datasheet does not give them.
  YAML::Emitter out;
  out.SetDoublePrecision(9);
  out << YAML::BeginMap;
  emit_vehicle_section(out, datasheet_vehicle(vehicle, errors, knowledge),
                       {{"empty_mass_kg", "datasheet kerb mass"},
                        {"cg_to_front_axle_m", "empty car, from the datasheet's axle loads"},
                        {"cornering_stiffness_front_n_per_rad", "at the empty axle load"}},
                       FieldSelection::kRequiredOrSet);
  emit_suspension(out, vehicle, errors);
  out << YAML::EndMap;
  os << out.c_str() << "\n" << VehicleBus(vehicle).can_config_yaml(dbc_file);
  return os.str();
}

}  // namespace vmass::sim

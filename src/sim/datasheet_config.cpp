#include "vmass/sim/datasheet_config.hpp"

#include <cstdio>
#include <sstream>

#include "vmass/sim/powertrain.hpp"
#include "vmass/sim/suspension.hpp"
#include "vmass/sim/vehicle_bus.hpp"

namespace vmass::sim {

namespace {

std::string num(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.9g", v);
  return buf;
}

void write_vehicle(std::ostringstream& os, const DrawnVehicle& d, bool errors, Knowledge k) {
  const TrueVehicle& v = d.vehicle;
  const KnowledgeErrors& e = d.errors;
  auto err = [&](double x) { return errors ? x : 0.0; };
  const AxleCorneringStiffness cs = static_cornering_stiffness(v, v.empty);
  const double radius =
      v.wheel_radius_m * (1.0 + (k == Knowledge::kDatasheetScale ? e.wheel_radius : 0.0));
  os << "vehicle:\n";
  os << "  empty_mass_kg: " << num(v.empty.mass_kg) << "        # datasheet kerb mass\n";
  os << "  max_mass_kg: " << num(d.max_mass_kg) << "\n";
  os << "  wheelbase_m: " << num(v.wheelbase_m) << "\n";
  os << "  cg_to_front_axle_m: " << num(v.empty.cg_x_m + err(e.cg_position_m))
     << "   # empty car, from the datasheet's axle loads\n";
  os << "  wheel_radius_m: " << num(radius) << "\n";
  os << "  brake_gain_n_per_pa: " << num(v.brake_gain_n_per_pa * (1.0 + err(e.brake_gain))) << "\n";
  os << "  steering_ratio: " << num(v.steering_ratio) << "\n";
  os << "  cornering_stiffness_front_n_per_rad: "
     << num(cs.front_n_per_rad * (1.0 + err(e.cornering_front))) << "   # at the empty axle load\n";
  os << "  cornering_stiffness_rear_n_per_rad: "
     << num(cs.rear_n_per_rad * (1.0 + err(e.cornering_rear))) << "\n";
  const double rot = 1.0 + err(e.rotating_mass);
  os << "  rotating_mass_kg: " << num(rotating_mass_kg(v.powertrain, 0, v.wheel_radius_m) * rot)
     << "\n";
  os << "  rotating_mass_by_gear_kg: [";
  for (int g = 1; g <= v.powertrain.gear_count(); ++g) {
    os << (g > 1 ? ", " : "") << num(rotating_mass_kg(v.powertrain, g, v.wheel_radius_m) * rot);
  }
  os << "]\n";
  if (v.powertrain.transmission == Transmission::kElectric) os << "  electric_drive: true\n";
  os << "  drag_area_m2: " << num(v.drag_area_m2 * (1.0 + err(e.drag_area))) << "\n";
  os << "  rolling_resistance_coeff: "
     << num(v.rolling_resistance_coeff * (1.0 + err(e.rolling_coeff))) << "\n";
  if (k == Knowledge::kDatasheetScale) {
    os << "  wheel_torque_accuracy_fraction: " << num(e.declared_torque_accuracy) << "\n";
    os << "  wheel_radius_accuracy_fraction: " << num(e.declared_radius_accuracy) << "\n";
  } else {
    os << "  wheel_torque_accuracy_fraction: 0\n";
    os << "  wheel_radius_accuracy_fraction: 0\n";
  }
  if (d.sensors.torque == TorqueSignal::kEngineTorque) {
    const PowertrainParams& p = v.powertrain;
    os << "  gear_ratios: [";
    for (std::size_t i = 0; i < p.gear_ratios.size(); ++i) {
      os << (i > 0 ? ", " : "") << num(p.gear_ratios[i]);
    }
    os << "]\n  final_drive_ratio: " << num(p.final_drive_ratio) << "\n";
    os << "  driveline_efficiency: " << num(p.efficiency) << "\n";
  }
}

void write_suspension(std::ostringstream& os, const DrawnVehicle& d, bool errors) {
  if (!d.sensors.deflection) return;
  const TrueVehicle& v = d.vehicle;
  os << "suspension:\n";
  if (v.rear_levelling) {
    os << "  levelled: true                # air suspension: the ride height carries no load\n";
    return;
  }
  const SuspensionParams& sp = v.rear_right_suspension;
  const StaticLoads empty = static_loads(v, v.empty);
  const double empty_reading =
      spring_compression(sp, empty.rear_right_n - sp.unsprung_mass_kg * v.gravity_mps2) -
      sp.sensor_reference_m;
  const double stiffness =
      sp.stiffness_n_per_m * (1.0 + (errors ? d.errors.suspension_stiffness : 0.0));
  const double knee = sp.knee_compression_m - sp.sensor_reference_m;
  // Eq. (3) inverted at the knee: the added load at the CG that reaches it.
  const double linear_range =
      2.0 * v.wheelbase_m * stiffness * (knee - empty_reading) / (v.empty.cg_x_m * v.gravity_mps2);
  os << "  stiffness_n_per_m: " << num(stiffness) << "   # vmass-calibrate on ballast\n";
  os << "  empty_deflection_m: " << num(empty_reading) << "\n";
  os << "  linear_range_kg: " << num(linear_range) << "\n";
  os << "  calibrated_range_kg: " << num(d.payload_capacity_kg) << "\n";
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
  write_vehicle(os, vehicle, errors, knowledge);
  write_suspension(os, vehicle, errors);
  os << VehicleBus(vehicle).can_config_yaml(dbc_file);
  return os.str();
}

}  // namespace vmass::sim

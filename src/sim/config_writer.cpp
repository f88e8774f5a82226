#include "vmass/sim/config_writer.hpp"

#include <sstream>

#include <yaml-cpp/yaml.h>

#include "text_file.hpp"
#include "vmass/config/suspension_section.hpp"
#include "vmass/sim/csv_writer.hpp"
#include "vmass/sim/suspension.hpp"

namespace vmass::sim {

ConfigValues make_config_values(const TrueVehicle& v, const MassProperties& loaded,
                                double tick_rate_hz, const CalibrationErrors& errors) {
  ConfigValues c;
  c.empty_mass_kg = v.empty.mass_kg;
  c.wheelbase_m = v.wheelbase_m;
  c.cg_to_front_axle_m = loaded.cg_x_m;
  c.wheel_radius_m = v.wheel_radius_m;
  c.brake_gain_n_per_pa = v.brake_gain_n_per_pa;
  c.steering_ratio = v.steering_ratio;
  const AxleCorneringStiffness cs = static_cornering_stiffness(v, loaded);
  c.cornering_stiffness_front_n_per_rad = cs.front_n_per_rad;
  c.cornering_stiffness_rear_n_per_rad = cs.rear_n_per_rad;
  c.rotating_mass_kg = rotating_mass_kg(v.powertrain, 0, v.wheel_radius_m);
  for (int g = 1; g <= v.powertrain.gear_count(); ++g) {
    c.rotating_mass_by_gear_kg.push_back(rotating_mass_kg(v.powertrain, g, v.wheel_radius_m));
  }
  c.gravity_mps2 = v.gravity_mps2;

  const SuspensionParams& sp = v.rear_right_suspension;
  const StaticLoads empty_loads = static_loads(v, v.empty);
  const double empty_sprung_n = empty_loads.rear_right_n - sp.unsprung_mass_kg * v.gravity_mps2;
  c.empty_deflection_m = spring_compression(sp, empty_sprung_n) - sp.sensor_reference_m;
  c.progressive_knee_m = sp.knee_compression_m - sp.sensor_reference_m;
  c.stiffness_n_per_m = sp.stiffness_n_per_m * errors.suspension_stiffness_scale;
  c.progressive_rate_n_per_m2 = sp.progressive_rate_n_per_m2 * errors.suspension_stiffness_scale;
  // Eq. (3) inverted at the knee: added load (at the centre of gravity) that reaches it.
  c.linear_range_kg = 2.0 * c.wheelbase_m * c.stiffness_n_per_m *
                      (c.progressive_knee_m - c.empty_deflection_m) /
                      (c.cg_to_front_axle_m * c.gravity_mps2);
  c.calibrated_range_kg = errors.calibrated_range_kg;

  c.tick_rate_hz = tick_rate_hz;
  return c;
}

void write_config_yaml(std::ostream& os, const ConfigValues& c,
                       const std::vector<std::string>& header_comment) {
  for (const std::string& line : header_comment)
    os << "#" << (line.empty() ? "" : " ") << line << '\n';
  YAML::Emitter e;
  e.SetDoublePrecision(12);
  e << YAML::BeginMap;
  e << YAML::Key << "vehicle" << YAML::Value << YAML::BeginMap;
  e << YAML::Key << "empty_mass_kg" << YAML::Value << c.empty_mass_kg;
  e << YAML::Key << "wheelbase_m" << YAML::Value << c.wheelbase_m;
  e << YAML::Key << "cg_to_front_axle_m" << YAML::Value << c.cg_to_front_axle_m
    << YAML::Comment("as loaded at the start of the scenario");
  e << YAML::Key << "wheel_radius_m" << YAML::Value << c.wheel_radius_m;
  e << YAML::Key << "brake_gain_n_per_pa" << YAML::Value << c.brake_gain_n_per_pa;
  e << YAML::Key << "steering_ratio" << YAML::Value << c.steering_ratio;
  e << YAML::Key << "cornering_stiffness_front_n_per_rad" << YAML::Value
    << c.cornering_stiffness_front_n_per_rad << YAML::Comment("small-slip, static axle load");
  e << YAML::Key << "cornering_stiffness_rear_n_per_rad" << YAML::Value
    << c.cornering_stiffness_rear_n_per_rad;
  e << YAML::Key << "rotating_mass_kg" << YAML::Value << c.rotating_mass_kg
    << YAML::Comment("clutch open (gear signal 0 during shifts)");
  e << YAML::Key << "rotating_mass_by_gear_kg" << YAML::Value << YAML::Flow << YAML::BeginSeq;
  for (double m : c.rotating_mass_by_gear_kg) e << m;
  e << YAML::EndSeq;
  e << YAML::Key << "gravity_mps2" << YAML::Value << c.gravity_mps2;
  e << YAML::EndMap;

  vmass::SuspensionParams suspension;  // the estimator's (config) parameters
  suspension.stiffness_n_per_m = c.stiffness_n_per_m;
  suspension.empty_deflection_m = c.empty_deflection_m;
  suspension.progressive_knee_m = c.progressive_knee_m;
  suspension.progressive_rate_n_per_m2 = c.progressive_rate_n_per_m2;
  suspension.linear_range_kg = c.linear_range_kg;
  suspension.calibrated_range_kg = c.calibrated_range_kg;
  emit_suspension_section(e, suspension, {"calibrated; see header"});

  e << YAML::Key << "estimator" << YAML::Value << YAML::BeginMap;
  e << YAML::Key << "type" << YAML::Value << "bayes" << YAML::Comment("or rls");
  // Nothing else: the estimator runs on its defaults, which must hold on any car (nothing here
  // is tuned to the simulator; docs/estimator.md).
  e << YAML::EndMap;
  e << YAML::EndMap;
  os << e.c_str() << '\n';
}

std::string write_config_file(const SimulationResult& result, const std::string& dir,
                              const CalibrationErrors& errors) {
  const TrueVehicle& v = result.vehicle;
  const ConfigValues c = make_config_values(v, result.initial_mass, result.tick_rate_hz, errors);
  const double true_c = v.rear_right_suspension.stiffness_n_per_m;
  std::vector<std::string> header = {
      "vmass config for the simulated car, written by vmass-sim.",
      "scenario " + result.scenario + ", seed " + std::to_string(result.seed) + ", noise " +
          std::string(noise_set_name(result.noise)) + ".",
      "Vehicle values match the simulated car (l_f and cornering stiffness at the starting load),",
      "except the suspension calibration: stiffness and progressive rate are " +
          format_number((1.0 - errors.suspension_stiffness_scale) * 100.0) +
          " % low (true c = " + format_number(true_c) + " N/m),",
      "and the deflection sensor has drifted " +
          format_number(result.sensors.rear_right_deflection_m.bias * 1000.0) +
          " mm since the empty reading was taken.",
      "True start mass " + format_number(result.initial_mass.mass_kg) +
          " kg: see truth.csv (mass_kg) for the mass over time.",
  };
  std::ostringstream os;
  write_config_yaml(os, c, header);
  return detail::write_text_file(dir + "/config.yaml", os.str());
}

}  // namespace vmass::sim

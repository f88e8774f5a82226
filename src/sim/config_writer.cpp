#include "vmass/sim/config_writer.hpp"

#include <sstream>

#include <yaml-cpp/yaml.h>

#include "vmass/config/estimator_section.hpp"
#include "vmass/config/suspension_section.hpp"
#include "vmass/config/vehicle_section.hpp"
#include "vmass/sim/csv_writer.hpp"
#include "vmass/sim/suspension.hpp"

namespace vmass::sim {

PipelineParams make_config_params(const TrueVehicle& v, const MassProperties& loaded,
                                  double tick_rate_hz, const CalibrationErrors& errors) {
  PipelineParams c;
  VehicleParams& cv = c.vehicle;
  cv.empty_mass_kg = v.empty.mass_kg;
  cv.wheelbase_m = v.wheelbase_m;
  cv.cg_to_front_axle_m = loaded.cg_x_m;
  cv.wheel_radius_m = v.wheel_radius_m;
  cv.brake_gain_n_per_pa = v.brake_gain_n_per_pa;
  cv.steering_ratio = v.steering_ratio;
  const AxleCorneringStiffness cs = static_cornering_stiffness(v, loaded);
  cv.cornering_stiffness_front_n_per_rad = cs.front_n_per_rad;
  cv.cornering_stiffness_rear_n_per_rad = cs.rear_n_per_rad;
  cv.rotating_mass_kg = rotating_mass_kg(v.powertrain, 0, v.wheel_radius_m);
  for (int g = 1; g <= v.powertrain.gear_count(); ++g) {
    cv.rotating_mass_by_gear_kg.push_back(rotating_mass_kg(v.powertrain, g, v.wheel_radius_m));
  }
  cv.gravity_mps2 = v.gravity_mps2;

  const SuspensionParams& sp = v.rear_right_suspension;
  vmass::SuspensionParams& spring = c.suspension;  // the estimator's (config) parameters
  const StaticLoads empty_loads = static_loads(v, v.empty);
  const double empty_sprung_n = empty_loads.rear_right_n - sp.unsprung_mass_kg * v.gravity_mps2;
  spring.empty_deflection_m = spring_compression(sp, empty_sprung_n) - sp.sensor_reference_m;
  spring.progressive_knee_m = sp.knee_compression_m - sp.sensor_reference_m;
  spring.stiffness_n_per_m = sp.stiffness_n_per_m * errors.suspension_stiffness_scale;
  spring.progressive_rate_n_per_m2 =
      sp.progressive_rate_n_per_m2 * errors.suspension_stiffness_scale;
  // Eq. (3) inverted at the knee: added load (at the centre of gravity) that reaches it.
  spring.linear_range_kg = 2.0 * cv.wheelbase_m * spring.stiffness_n_per_m *
                           (spring.progressive_knee_m - spring.empty_deflection_m) /
                           (cv.cg_to_front_axle_m * cv.gravity_mps2);
  spring.calibrated_range_kg = errors.calibrated_range_kg;

  c.estimator.differencing.tick_rate_hz = tick_rate_hz;
  return c;
}

void write_config_yaml(std::ostream& os, const PipelineParams& c,
                       const std::vector<std::string>& header_comment) {
  for (const std::string& line : header_comment)
    os << "#" << (line.empty() ? "" : " ") << line << '\n';
  YAML::Emitter e;
  e.SetDoublePrecision(12);
  e << YAML::BeginMap;
  e << YAML::Key << "vehicle" << YAML::Value << YAML::BeginMap;
  emit_fields(e, kVehicleFields, c.vehicle,
              {{"cg_to_front_axle_m", "as loaded at the start of the scenario"},
               {"cornering_stiffness_front_n_per_rad", "small-slip, static axle load"},
               {"rotating_mass_kg", "clutch open (gear signal 0 during shifts)"}},
              {"empty_mass_kg", "wheelbase_m", "cg_to_front_axle_m", "wheel_radius_m",
               "brake_gain_n_per_pa", "steering_ratio", "cornering_stiffness_front_n_per_rad",
               "cornering_stiffness_rear_n_per_rad", "rotating_mass_kg", "rotating_mass_by_gear_kg",
               "gravity_mps2"});
  e << YAML::EndMap;
  emit_suspension_section(e, c.suspension, {{"stiffness_n_per_m", "calibrated; see header"}});
  // The estimator runs on its defaults, which must hold on any car (nothing here is tuned to
  // the simulator; docs/estimator.md): its type, and the scenario's tick rate if not the default.
  e << YAML::Key << "estimator" << YAML::Value << YAML::BeginMap;
  emit_fields(e, kEstimatorFields, c.estimator, {{"type", "or rls"}}, {"type"});
  emit_fields(e, kDifferencingFields, c.estimator.differencing, {}, FieldSelection::kRequiredOrSet);
  e << YAML::EndMap;
  e << YAML::EndMap;
  os << e.c_str() << '\n';
}

std::string demo_config_yaml(const SimulationResult& result, const CalibrationErrors& errors) {
  const TrueVehicle& v = result.vehicle;
  const PipelineParams c = make_config_params(v, result.initial_mass, result.tick_rate_hz, errors);
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
  return os.str();
}

}  // namespace vmass::sim

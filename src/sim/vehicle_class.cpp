// The vehicle classes' names and the population's definition as text (its ranges are the table
// in vehicle_class_table.cpp, its draw rules population.cpp): what docs/accuracy.md hashes.
#include "vmass/sim/vehicle_class.hpp"

#include <cstdio>
#include <sstream>

#include "vmass/sim/population.hpp"
#include "vmass/sim/random_stream.hpp"

namespace vmass::sim {

namespace {

void print_range(std::ostringstream& os, const char* cls, const char* name, const Range& r) {
  char buf[256];
  std::snprintf(buf, sizeof buf, "%s.%s = [%.9g, %.9g] %s\n", cls, name, r.low, r.high, r.source);
  os << buf;
}

template <typename E, typename NameFn>
void print_weighted(std::ostringstream& os, const char* cls, const char* name,
                    const std::vector<Weighted<E>>& list, NameFn name_of) {
  os << cls << '.' << name << " =";
  for (const auto& w : list) os << ' ' << name_of(w.value) << ':' << w.weight;
  os << '\n';
}

}  // namespace

std::string_view vehicle_class_name(VehicleClass c) {
  switch (c) {
    case VehicleClass::kCityCar:
      return "city_car";
    case VehicleClass::kCompact:
      return "compact";
    case VehicleClass::kSaloon:
      return "saloon";
    case VehicleClass::kSuv:
      return "suv";
    case VehicleClass::kVan:
      return "van";
    case VehicleClass::kPickup:
      return "pickup";
    case VehicleClass::kHeavyTruck:
      return "heavy_truck";
    case VehicleClass::kCount:
      break;
  }
  return "unknown";
}

std::optional<VehicleClass> parse_vehicle_class(std::string_view name) {
  for (int i = 0; i < kVehicleClassCount; ++i) {
    const auto c = static_cast<VehicleClass>(i);
    if (vehicle_class_name(c) == name) return c;
  }
  return std::nullopt;
}

std::string population_sources() {
  return "[TA] EU type-approval and manufacturer datasheets of the example vehicles\n"
         "[GIL] T. D. Gillespie, Fundamentals of Vehicle Dynamics, SAE, 1992\n"
         "[WONG] J. Y. Wong, Theory of Ground Vehicles, 4th ed., Wiley, 2008\n"
         "[HUCHO] W.-H. Hucho (ed.), Aerodynamics of Road Vehicles, 4th ed., SAE, 1998\n"
         "[PAC] H. B. Pacejka, Tyre and Vehicle Dynamics, 3rd ed., Butterworth-Heinemann, 2012\n"
         "[RCVD] W. F. Milliken, D. L. Milliken, Race Car Vehicle Dynamics, SAE, 1995\n"
         "[CRO] B. Mashadi, D. Crolla, Vehicle Powertrain Systems, Wiley, 2012, ch. 6\n"
         "[J2452] SAE J2452, Stepwise Coastdown Methodology for Measuring Tire Rolling "
         "Resistance\n"
         "[R39] UN ECE Regulation No. 39, speedometer and odometer\n"
         "[R48] UN ECE Regulation No. 48, installation of lighting (headlamp levelling)\n"
         "[ISO8608] ISO 8608, Mechanical vibration - Road surface profiles\n"
         "[LIMP] R. Limpert, Brake Design and Safety, 3rd ed., SAE, 2011\n"
         "[ESC] datasheets of ESC inertial sensor clusters\n"
         "[ours] engineering judgement, with the reason beside the range\n";
}

std::string population_definition_text() {
  std::ostringstream os;
  for (const ClassDefinition& c : vehicle_classes()) {
    const std::string n(vehicle_class_name(c.id));
    const char* k = n.c_str();
    os << n << ".examples = " << c.examples << '\n';
    print_range(os, k, "empty_mass_kg", c.empty_mass_kg);
    print_range(os, k, "electric_extra_mass_fraction", c.electric_extra_mass_fraction);
    print_range(os, k, "payload_capacity_kg", c.payload_capacity_kg);
    print_range(os, k, "wheelbase_m", c.wheelbase_m);
    print_range(os, k, "track_m", c.track_m);
    print_range(os, k, "front_weight_share", c.front_weight_share);
    print_range(os, k, "cg_height_m", c.cg_height_m);
    print_range(os, k, "drag_area_m2", c.drag_area_m2);
    print_range(os, k, "rolling_f0", c.rolling_f0);
    print_range(os, k, "rolling_f2_s2_per_m2", c.rolling_f2_s2_per_m2);
    print_range(os, k, "driveline_viscous_n_per_mps", c.driveline_viscous_n_per_mps);
    print_range(os, k, "wheel_radius_m", c.wheel_radius_m);
    print_range(os, k, "power_kw", c.power_kw);
    print_range(os, k, "wheel_inertia_kgm2", c.wheel_inertia_kgm2);
    print_range(os, k, "engine_inertia_kgm2", c.engine_inertia_kgm2);
    print_range(os, k, "steering_ratio", c.steering_ratio);
    print_range(os, k, "cornering_per_load_front", c.cornering_per_load_front);
    print_range(os, k, "cornering_per_load_rear", c.cornering_per_load_rear);
    os << n << ".tyre_reference_load_n = " << c.tyre_reference_load_n << '\n';
    print_range(os, k, "rear_wheel_rate_n_per_m", c.rear_wheel_rate_n_per_m);
    print_range(os, k, "roll_gradient_deg_per_g", c.roll_gradient_deg_per_g);
    print_range(os, k, "pitch_gradient_deg_per_g", c.pitch_gradient_deg_per_g);
    print_range(os, k, "mode_first_gear_hz", c.mode_first_gear_hz);
    print_range(os, k, "mode_top_gear_hz", c.mode_top_gear_hz);
    print_range(os, k, "vibration_rms_mps2", c.vibration_rms_mps2);
    print_range(os, k, "brake_full_pressure_bar", c.brake_full_pressure_bar);
    print_weighted(os, k, "transmissions", c.transmissions, transmission_name);
    print_weighted(os, k, "driven_axles", c.driven_axles, driven_axle_name);
    os << n << ".probabilities = deflection " << c.p_deflection_sensor << ", brake_pressure "
       << c.p_brake_pressure << ", engine_torque_only " << c.p_engine_torque_only << ", levelling "
       << c.p_levelling << ", display_speed_only " << c.p_display_speed_only << ", no_lateral "
       << c.p_no_lateral << '\n';
  }
  const CommonRanges& r = common_ranges();
  const char* k = "common";
  print_range(os, k, "driveline_lag_s", r.driveline_lag_s);
  print_range(os, k, "mode_damping_ratio", r.mode_damping_ratio);
  print_range(os, k, "torque_time_constant_s", r.torque_time_constant_s);
  print_range(os, k, "tc_stall_torque_ratio", r.tc_stall_torque_ratio);
  print_range(os, k, "tc_coupling_speed_ratio", r.tc_coupling_speed_ratio);
  print_range(os, k, "tc_lockup_speed_mps", r.tc_lockup_speed_mps);
  print_range(os, k, "tc_model_error", r.tc_model_error);
  print_range(os, k, "creep_force_per_weight", r.creep_force_per_weight);
  print_range(os, k, "drag_report_error", r.drag_report_error);
  print_range(os, k, "accessory_power_w", r.accessory_power_w);
  print_range(os, k, "regen_max_decel_g", r.regen_max_decel_g);
  print_range(os, k, "imu_filter_cutoff_hz", r.imu_filter_cutoff_hz);
  print_range(os, k, "imu_bias_mps2", r.imu_bias_mps2);
  print_range(os, k, "imu_drift_mps2_per_sqrt_s", r.imu_drift_mps2_per_sqrt_s);
  print_range(os, k, "imu_noise_std_mps2", r.imu_noise_std_mps2);
  print_range(os, k, "imu_vibration_frequency_hz", r.imu_vibration_frequency_hz);
  print_range(os, k, "imu_misalignment_deg", r.imu_misalignment_deg);
  print_range(os, k, "imu_lever_forward_m", r.imu_lever_forward_m);
  print_range(os, k, "imu_lever_left_m", r.imu_lever_left_m);
  print_range(os, k, "speed_radius_error_fraction", r.speed_radius_error_fraction);
  print_range(os, k, "display_overread_fraction", r.display_overread_fraction);
  print_range(os, k, "brake_pressure_offset_bar", r.brake_pressure_offset_bar);
  print_range(os, k, "brake_fade_max_fraction", r.brake_fade_max_fraction);
  print_range(os, k, "empty_mass_deviation_fraction", r.empty_mass_deviation_fraction);
  print_range(os, k, "ecu_latency_s", r.ecu_latency_s);
  os << population_rules_text();
  return os.str();
}

std::string population_definition_hash() {
  const std::string text = population_definition_text();
  const std::uint64_t h = hash_name(text.c_str());
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(h));
  return buf;
}

}  // namespace vmass::sim

#include "vmass/sim/vehicle_class.hpp"

#include <cstdio>
#include <sstream>

#include "vmass/sim/population.hpp"
#include "vmass/sim/random_stream.hpp"

namespace vmass::sim {

namespace {

using T = Transmission;
using A = DrivenAxle;

ClassDefinition city_car() {
  ClassDefinition c;
  c.id = VehicleClass::kCityCar;
  c.examples = "VW up!, Fiat 500, Toyota Aygo, Renault Zoe (electric)";
  c.empty_mass_kg = {900, 1200, "[TA]"};
  c.electric_extra_mass_fraction = {0.15, 0.30, "[TA] electric variants (Zoe, e-up!)"};
  c.payload_capacity_kg = {350, 450, "[TA]"};
  c.wheelbase_m = {2.30, 2.55, "[TA]"};
  c.track_m = {1.38, 1.50, "[TA]"};
  c.front_weight_share = {0.59, 0.64, "[GIL] front-engined front-wheel drive"};
  c.cg_height_m = {0.50, 0.57, "[GIL]"};
  c.drag_area_m2 = {0.60, 0.70, "[HUCHO]"};
  c.rolling_f0 = {0.009, 0.012, "[WONG]"};
  c.rolling_f2_s2_per_m2 = {3e-6, 6e-6, "[J2452]"};
  c.driveline_viscous_n_per_mps = {0.5, 1.5, "[WONG] ~1-3 % of drive power at speed"};
  c.wheel_radius_m = {0.27, 0.30, "[TA] 165/65 R14 - 185/55 R15"};
  c.power_kw = {45, 80, "[TA]"};
  c.wheel_inertia_kgm2 = {2.6, 3.6, "[ours] four 0.6-0.8 kg m^2 wheels with discs, shafts"};
  c.engine_inertia_kgm2 = {0.08, 0.15, "[ours] 1.0-1.2 l engines with flywheel"};
  c.steering_ratio = {14, 17, "[TA]"};
  c.cornering_per_load_front = {14, 19, "[PAC]"};
  c.cornering_per_load_rear = {17, 23, "[PAC]"};
  c.tyre_reference_load_n = 3500;
  c.rear_wheel_rate_n_per_m = {17000, 24000, "[GIL] ride frequency 1.2-1.5 Hz"};
  c.roll_gradient_deg_per_g = {3.0, 5.0, "[RCVD] passenger cars"};
  c.pitch_gradient_deg_per_g = {0.8, 1.6, "[RCVD]"};
  c.mode_first_gear_hz = {2.0, 4.0, "[CRO]"};
  c.mode_top_gear_hz = {6.0, 10.0, "[CRO]"};
  c.vibration_rms_mps2 = {0.03, 0.07, "[ours] light car on a smooth road, after the IMU mount"};
  c.brake_full_pressure_bar = {90, 130, "[GIL] [LIMP]"};
  c.transmissions = {
      {T::kManual, 0.45}, {T::kAutomatedManual, 0.1}, {T::kDualClutch, 0.15}, {T::kElectric, 0.3}};
  c.driven_axles = {{A::kFront, 1.0}};
  c.p_deflection_sensor = 0.3;
  c.p_brake_pressure = 0.85;
  c.p_engine_torque_only = 0.2;
  c.p_display_speed_only = 0.15;
  return c;
}

ClassDefinition compact() {
  ClassDefinition c;
  c.id = VehicleClass::kCompact;
  c.examples = "VW Golf VIII, Ford Focus, Toyota Corolla, VW ID.3 (electric)";
  c.empty_mass_kg = {1200, 1500, "[TA]"};
  c.electric_extra_mass_fraction = {0.20, 0.35, "[TA]"};
  c.payload_capacity_kg = {450, 560, "[TA]"};
  c.wheelbase_m = {2.55, 2.75, "[TA]"};
  c.track_m = {1.50, 1.60, "[TA]"};
  c.front_weight_share = {0.57, 0.63, "[GIL]"};
  c.cg_height_m = {0.50, 0.57, "[GIL]"};
  c.drag_area_m2 = {0.60, 0.70, "[HUCHO]"};
  c.rolling_f0 = {0.008, 0.011, "[WONG]"};
  c.rolling_f2_s2_per_m2 = {3e-6, 6e-6, "[J2452]"};
  c.driveline_viscous_n_per_mps = {0.5, 2.0, "[WONG]"};
  c.wheel_radius_m = {0.30, 0.33, "[TA] 205/55 R16 - 225/45 R17"};
  c.power_kw = {80, 150, "[TA]"};
  c.wheel_inertia_kgm2 = {3.2, 4.4, "[ours]"};
  c.engine_inertia_kgm2 = {0.12, 0.22, "[ours]"};
  c.steering_ratio = {13.5, 16.5, "[TA]"};
  c.cornering_per_load_front = {15, 20, "[PAC]"};
  c.cornering_per_load_rear = {18, 24, "[PAC]"};
  c.tyre_reference_load_n = 4000;
  c.rear_wheel_rate_n_per_m = {20000, 30000, "[GIL]"};
  c.roll_gradient_deg_per_g = {2.8, 4.5, "[RCVD]"};
  c.pitch_gradient_deg_per_g = {0.7, 1.5, "[RCVD]"};
  c.mode_first_gear_hz = {2.0, 4.0, "[CRO]"};
  c.mode_top_gear_hz = {6.0, 10.0, "[CRO]"};
  c.vibration_rms_mps2 = {0.02, 0.06, "[ours]"};
  c.brake_full_pressure_bar = {90, 130, "[GIL] [LIMP]"};
  c.transmissions = {
      {T::kManual, 0.3}, {T::kDualClutch, 0.3}, {T::kAutomatic, 0.15}, {T::kElectric, 0.25}};
  c.driven_axles = {{A::kFront, 0.9}, {A::kAll, 0.1}};
  c.p_deflection_sensor = 0.45;
  c.p_brake_pressure = 0.9;
  c.p_engine_torque_only = 0.15;
  c.p_display_speed_only = 0.1;
  return c;
}

ClassDefinition saloon() {
  ClassDefinition c;
  c.id = VehicleClass::kSaloon;
  c.examples = "VW Passat B8, BMW 5 Series G30, Mercedes E-Class W213, Tesla Model S";
  c.empty_mass_kg = {1450, 1850, "[TA]"};
  c.electric_extra_mass_fraction = {0.15, 0.30, "[TA]"};
  c.payload_capacity_kg = {500, 620, "[TA]"};
  c.wheelbase_m = {2.75, 3.00, "[TA]"};
  c.track_m = {1.55, 1.65, "[TA]"};
  c.front_weight_share = {0.50, 0.58, "[GIL] longitudinal engines, rear-wheel drive"};
  c.cg_height_m = {0.50, 0.56, "[GIL]"};
  c.drag_area_m2 = {0.55, 0.66, "[HUCHO]"};
  c.rolling_f0 = {0.008, 0.011, "[WONG]"};
  c.rolling_f2_s2_per_m2 = {3e-6, 6e-6, "[J2452]"};
  c.driveline_viscous_n_per_mps = {1.0, 3.0, "[WONG]"};
  c.wheel_radius_m = {0.31, 0.35, "[TA] 215/60 R16 - 245/40 R19"};
  c.power_kw = {110, 250, "[TA]"};
  c.wheel_inertia_kgm2 = {4.0, 5.5, "[ours]"};
  c.engine_inertia_kgm2 = {0.15, 0.30, "[ours]"};
  c.steering_ratio = {13.5, 16.5, "[TA]"};
  c.cornering_per_load_front = {15, 20, "[PAC]"};
  c.cornering_per_load_rear = {18, 24, "[PAC]"};
  c.tyre_reference_load_n = 4500;
  c.rear_wheel_rate_n_per_m = {24000, 35000, "[GIL]"};
  c.roll_gradient_deg_per_g = {2.5, 4.0, "[RCVD]"};
  c.pitch_gradient_deg_per_g = {0.6, 1.4, "[RCVD]"};
  c.mode_first_gear_hz = {2.0, 4.0, "[CRO]"};
  c.mode_top_gear_hz = {6.0, 10.0, "[CRO]"};
  c.vibration_rms_mps2 = {0.02, 0.05, "[ours]"};
  c.brake_full_pressure_bar = {90, 130, "[GIL] [LIMP]"};
  c.transmissions = {{T::kAutomatic, 0.6}, {T::kDualClutch, 0.15}, {T::kElectric, 0.25}};
  c.driven_axles = {{A::kRear, 0.4}, {A::kFront, 0.3}, {A::kAll, 0.3}};
  c.p_deflection_sensor = 0.6;
  c.p_brake_pressure = 0.9;
  c.p_engine_torque_only = 0.1;
  c.p_display_speed_only = 0.05;
  return c;
}

ClassDefinition suv() {
  ClassDefinition c;
  c.id = VehicleClass::kSuv;
  c.examples = "VW Tiguan, BMW X5 G05, Audi Q7, Tesla Model Y";
  c.empty_mass_kg = {1600, 2400, "[TA]"};
  c.electric_extra_mass_fraction = {0.10, 0.25, "[TA]"};
  c.payload_capacity_kg = {500, 750, "[TA]"};
  c.wheelbase_m = {2.65, 3.00, "[TA]"};
  c.track_m = {1.58, 1.70, "[TA]"};
  c.front_weight_share = {0.50, 0.57, "[GIL]"};
  c.cg_height_m = {0.62, 0.75, "[GIL]"};
  c.drag_area_m2 = {0.80, 1.05, "[HUCHO]"};
  c.rolling_f0 = {0.009, 0.012, "[WONG]"};
  c.rolling_f2_s2_per_m2 = {4e-6, 7e-6, "[J2452]"};
  c.driveline_viscous_n_per_mps = {1.5, 4.0, "[WONG]"};
  c.wheel_radius_m = {0.34, 0.38, "[TA] 235/65 R17 - 275/45 R21"};
  c.power_kw = {110, 300, "[TA]"};
  c.wheel_inertia_kgm2 = {5.0, 7.5, "[ours]"};
  c.engine_inertia_kgm2 = {0.15, 0.35, "[ours]"};
  c.steering_ratio = {14, 17, "[TA]"};
  c.cornering_per_load_front = {13, 18, "[PAC]"};
  c.cornering_per_load_rear = {16, 22, "[PAC]"};
  c.tyre_reference_load_n = 5500;
  c.rear_wheel_rate_n_per_m = {28000, 45000, "[GIL]"};
  c.roll_gradient_deg_per_g = {3.5, 6.0, "[RCVD] higher CG, softer roll"};
  c.pitch_gradient_deg_per_g = {0.8, 1.8, "[RCVD]"};
  c.mode_first_gear_hz = {2.0, 4.0, "[CRO]"};
  c.mode_top_gear_hz = {6.0, 10.0, "[CRO]"};
  c.vibration_rms_mps2 = {0.03, 0.07, "[ours]"};
  c.brake_full_pressure_bar = {90, 130, "[GIL] [LIMP]"};
  c.transmissions = {{T::kAutomatic, 0.65}, {T::kDualClutch, 0.1}, {T::kElectric, 0.25}};
  c.driven_axles = {{A::kAll, 0.6}, {A::kFront, 0.25}, {A::kRear, 0.15}};
  c.p_deflection_sensor = 0.7;
  c.p_brake_pressure = 0.9;
  c.p_engine_torque_only = 0.1;
  c.p_levelling = 0.3;
  c.p_display_speed_only = 0.05;
  return c;
}

ClassDefinition van() {
  ClassDefinition c;
  c.id = VehicleClass::kVan;
  c.examples = "Ford Transit Custom, VW Transporter T6.1, Renault Trafic, Mercedes Vito";
  c.empty_mass_kg = {1750, 2400, "[TA]"};
  c.electric_extra_mass_fraction = {0.15, 0.30, "[TA]"};
  c.payload_capacity_kg = {900, 1400, "[TA]"};
  c.wheelbase_m = {3.00, 3.70, "[TA]"};
  c.track_m = {1.62, 1.75, "[TA]"};
  c.front_weight_share = {0.55, 0.63, "[GIL] empty van, engine ahead"};
  c.cg_height_m = {0.75, 0.90, "[GIL]"};
  c.drag_area_m2 = {1.10, 1.40, "[HUCHO]"};
  c.rolling_f0 = {0.008, 0.011, "[WONG] C-type tyres"};
  c.rolling_f2_s2_per_m2 = {3e-6, 6e-6, "[J2452]"};
  c.driveline_viscous_n_per_mps = {1.5, 4.0, "[WONG]"};
  c.wheel_radius_m = {0.33, 0.36, "[TA] 215/65 R16C - 235/65 R16C"};
  c.power_kw = {80, 150, "[TA]"};
  c.wheel_inertia_kgm2 = {5.0, 7.0, "[ours]"};
  c.engine_inertia_kgm2 = {0.20, 0.35, "[ours] diesel with dual-mass flywheel"};
  c.steering_ratio = {15, 19, "[TA]"};
  c.cornering_per_load_front = {11, 16, "[PAC] C-type tyres"};
  c.cornering_per_load_rear = {13, 18, "[PAC]"};
  c.tyre_reference_load_n = 6500;
  c.rear_wheel_rate_n_per_m = {45000, 90000, "[GIL] load-carrying rear springs"};
  c.roll_gradient_deg_per_g = {4.0, 7.0, "[RCVD]"};
  c.pitch_gradient_deg_per_g = {0.8, 2.0, "[RCVD]"};
  c.mode_first_gear_hz = {2.0, 4.0, "[CRO]"};
  c.mode_top_gear_hz = {6.0, 10.0, "[CRO]"};
  c.vibration_rms_mps2 = {0.04, 0.09, "[ours] stiffer springs"};
  c.brake_full_pressure_bar = {100, 140, "[GIL] [LIMP]"};
  c.transmissions = {{T::kManual, 0.5}, {T::kAutomatic, 0.4}, {T::kElectric, 0.1}};
  c.driven_axles = {{A::kFront, 0.5}, {A::kRear, 0.4}, {A::kAll, 0.1}};
  c.p_deflection_sensor = 0.4;
  c.p_brake_pressure = 0.85;
  c.p_engine_torque_only = 0.2;
  c.p_levelling = 0.15;
  c.p_display_speed_only = 0.1;
  return c;
}

ClassDefinition pickup() {
  ClassDefinition c;
  c.id = VehicleClass::kPickup;
  c.examples = "Toyota Hilux AN120, Ford Ranger, Ford F-150, VW Amarok";
  c.empty_mass_kg = {1900, 2500, "[TA]"};
  c.electric_extra_mass_fraction = {0.2, 0.3, "[TA]"};
  c.payload_capacity_kg = {700, 1100, "[TA]"};
  c.wheelbase_m = {3.00, 3.70, "[TA]"};
  c.track_m = {1.55, 1.70, "[TA]"};
  c.front_weight_share = {0.55, 0.61, "[GIL] empty bed"};
  c.cg_height_m = {0.72, 0.85, "[GIL]"};
  c.drag_area_m2 = {1.00, 1.25, "[HUCHO]"};
  c.rolling_f0 = {0.009, 0.013, "[WONG] light-truck tyres"};
  c.rolling_f2_s2_per_m2 = {4e-6, 7e-6, "[J2452]"};
  c.driveline_viscous_n_per_mps = {2.0, 6.0, "[WONG] solid rear axle, transfer case"};
  c.wheel_radius_m = {0.37, 0.41, "[TA] 265/65 R17 - 275/60 R20"};
  c.power_kw = {110, 300, "[TA]"};
  c.wheel_inertia_kgm2 = {6.0, 9.0, "[ours]"};
  c.engine_inertia_kgm2 = {0.20, 0.40, "[ours]"};
  c.steering_ratio = {16, 20, "[TA]"};
  c.cornering_per_load_front = {11, 16, "[PAC] LT tyres"};
  c.cornering_per_load_rear = {13, 18, "[PAC]"};
  c.tyre_reference_load_n = 6500;
  c.rear_wheel_rate_n_per_m = {60000, 120000, "[GIL] leaf springs"};
  c.roll_gradient_deg_per_g = {4.0, 7.0, "[RCVD]"};
  c.pitch_gradient_deg_per_g = {0.8, 2.0, "[RCVD]"};
  c.mode_first_gear_hz = {2.0, 4.0, "[CRO]"};
  c.mode_top_gear_hz = {6.0, 10.0, "[CRO]"};
  c.vibration_rms_mps2 = {0.04, 0.10, "[ours] leaf springs, solid axle"};
  c.brake_full_pressure_bar = {100, 140, "[GIL] [LIMP]"};
  c.transmissions = {{T::kAutomatic, 0.7}, {T::kManual, 0.3}};
  c.driven_axles = {{A::kRear, 0.4}, {A::kAll, 0.6}};
  c.p_deflection_sensor = 0.35;
  c.p_brake_pressure = 0.85;
  c.p_engine_torque_only = 0.25;
  c.p_display_speed_only = 0.1;
  return c;
}

ClassDefinition heavy_truck() {
  ClassDefinition c;
  c.id = VehicleClass::kHeavyTruck;
  c.examples = "rigid three-axle 26 t: Mercedes Actros/Arocs 2630, Volvo FM 6x2, MAN TGS 26";
  c.empty_mass_kg = {9000, 12500, "[TA]"};
  c.electric_extra_mass_fraction = {0.0, 0.0, "[ours] no electric trucks in this population"};
  c.payload_capacity_kg = {13500, 17000, "[TA] 26 t GVW"};
  c.wheelbase_m = {4.5, 6.0, "[TA] front axle to the tandem's centre"};
  c.track_m = {2.00, 2.10, "[TA]"};
  c.front_weight_share = {0.50, 0.60, "[TA] empty chassis with body"};
  c.cg_height_m = {1.00, 1.30, "[WONG]"};
  c.drag_area_m2 = {5.5, 7.5, "[HUCHO] [WONG]"};
  c.rolling_f0 = {0.005, 0.007, "[WONG] truck tyres"};
  c.rolling_f2_s2_per_m2 = {1e-6, 3e-6, "[J2452]"};
  c.driveline_viscous_n_per_mps = {150, 310, "[WONG] ~9.5 kN at 31 m/s observed by a partner team"};
  c.wheel_radius_m = {0.49, 0.53, "[TA] 315/80 R22.5"};
  c.power_kw = {250, 400, "[TA]"};
  c.wheel_inertia_kgm2 = {100, 160, "[ours] ten wheels with drums or discs, axles"};
  c.engine_inertia_kgm2 = {2.5, 4.0, "[ours] 11-13 l engine with flywheel"};
  c.steering_ratio = {18, 24, "[TA]"};
  c.cornering_per_load_front = {6, 9, "[PAC] truck tyres"};
  c.cornering_per_load_rear = {7, 10, "[PAC]"};
  c.tyre_reference_load_n = 25000;
  c.rear_wheel_rate_n_per_m = {400000, 800000, "[WONG] leaf-sprung tandem, per wheel"};
  c.roll_gradient_deg_per_g = {4.0, 8.0, "[ours] high CG, stiff springs"};
  c.pitch_gradient_deg_per_g = {0.5, 1.2, "[ours] long wheelbase"};
  c.mode_first_gear_hz = {1.2, 2.5, "[ours] heavier reflected inertia than cars ([CRO] scaled)"};
  c.mode_top_gear_hz = {3.5, 6.0, "[ours]"};
  c.vibration_rms_mps2 = {0.06, 0.15, "[ours] cab-mounted ESC unit"};
  c.brake_full_pressure_bar = {6, 8, "[LIMP] air brakes"};
  c.transmissions = {{T::kAutomatedManual, 0.85}, {T::kAutomatic, 0.15}};
  c.driven_axles = {{A::kRear, 1.0}};
  c.p_deflection_sensor = 0.5;
  c.p_brake_pressure = 0.9;
  c.p_engine_torque_only = 0.3;
  c.p_levelling = 0.8;
  c.p_display_speed_only = 0.05;
  return c;
}

CommonRanges make_common() {
  CommonRanges r;
  r.driveline_lag_s = {0.010, 0.040, "[CRO] actuation and ECU computation"};
  r.mode_damping_ratio = {0.05, 0.30, "[CRO] lightly damped"};
  r.torque_time_constant_s = {0.06, 0.20, "[ours] turbocharged engines; electric 0.02-0.05"};
  r.tc_stall_torque_ratio = {1.8, 2.3, "[CRO]"};
  r.tc_coupling_speed_ratio = {0.82, 0.90, "[CRO]"};
  r.tc_lockup_speed_mps = {5.0, 12.0, "[ours] lock-up from 2nd gear"};
  r.tc_model_error = {-0.25, 0.25, "[ours] the TCU's converter map against the real one"};
  r.creep_force_per_weight = {0.03, 0.05, "[ours] creep moves a car on the flat"};
  r.drag_report_error = {-0.4, 0.4, "[ours] drag torque maps are the least accurate part"};
  r.accessory_power_w = {1000, 3000, "[ours] belt-driven A/C compressor (trucks x2)"};
  r.regen_max_decel_g = {0.12, 0.25, "[TA] one-pedal and blended regen limits"};
  r.imu_filter_cutoff_hz = {20, 40, "[ESC]"};
  r.imu_bias_mps2 = {-0.08, 0.08, "[ESC] zero-g offset after mounting"};
  r.imu_drift_mps2_per_sqrt_s = {2e-4, 1e-3, "[ESC] temperature drift as a random walk"};
  r.imu_noise_std_mps2 = {0.01, 0.03, "[ESC] per 100 Hz sample"};
  r.imu_vibration_frequency_hz = {8, 25, "[ours] wheel hop and body-mount modes"};
  r.imu_misalignment_deg = {-1.0, 1.0, "[ours] mounting tolerance"};
  r.imu_lever_forward_m = {-0.3, 0.5, "[ours] ESC unit under the seats or in the tunnel"};
  r.imu_lever_left_m = {-0.2, 0.2, "[ours]"};
  r.speed_radius_error_fraction = {-0.015, 0.015,
                                   "[ours] tyre wear, pressure, load vs the ESC's radius"};
  r.display_overread_fraction = {0.01, 0.04, "[R39]"};
  r.brake_pressure_offset_bar = {0.0, 0.3, "[ours] sensor zero offset"};
  r.brake_fade_max_fraction = {0.15, 0.35, "[LIMP]"};
  r.empty_mass_deviation_fraction = {-0.02, 0.04, "[TA] fuel level, options, tolerances"};
  r.ecu_latency_s = {0.0, 0.040, "[ours] sensor filtering and gateway delays"};
  return r;
}

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

const std::vector<ClassDefinition>& vehicle_classes() {
  static const std::vector<ClassDefinition> classes = {city_car(), compact(), saloon(),     suv(),
                                                       van(),      pickup(),  heavy_truck()};
  return classes;
}

const ClassDefinition& class_definition(VehicleClass c) {
  return vehicle_classes()[static_cast<std::size_t>(c)];
}

const CommonRanges& common_ranges() {
  static const CommonRanges r = make_common();
  return r;
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

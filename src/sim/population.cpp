#include "vmass/sim/population.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "vmass/sim/random_stream.hpp"
#include "vmass/sim/suspension.hpp"
#include "vmass/sim/truck_population.hpp"

namespace vmass::sim {

namespace {

constexpr double kRpm = 3.14159265358979323846 / 30.0;  // rad/s per rpm
constexpr double kG = 9.80665;

double draw(RandomStream& rng, const Range& r) { return rng.uniform(r.low, r.high); }

template <typename E>
E pick(RandomStream& rng, const std::vector<Weighted<E>>& list) {
  double total = 0.0;
  for (const auto& w : list) total += w.weight;
  double u = rng.uniform() * total;
  for (const auto& w : list) {
    if (u < w.weight) return w.value;
    u -= w.weight;
  }
  return list.back().value;
}

// Gear sets by transmission (ratios of gear 1..N, before a +-5 % scale per vehicle); the final
// drive is chosen for the engine speed in top gear at cruising speed.
std::vector<double> gear_set(Transmission t, VehicleClass c, RandomStream& rng) {
  if (t == Transmission::kElectric) return {1.0};
  if (c == VehicleClass::kHeavyTruck) {
    if (t == Transmission::kAutomatic) return {3.51, 1.91, 1.43, 1.00, 0.75, 0.64};
    return {14.9, 11.7, 9.0, 7.1, 5.6, 4.4, 3.4, 2.6, 2.0, 1.6, 1.3, 1.0};
  }
  switch (t) {
    case Transmission::kManual:
      return rng.chance(0.4) ? std::vector<double>{3.6, 1.95, 1.28, 0.95, 0.76}
                             : std::vector<double>{3.6, 2.1, 1.4, 1.05, 0.85, 0.70};
    case Transmission::kAutomatedManual:
      return {3.6, 1.95, 1.28, 0.95, 0.76};
    case Transmission::kDualClutch:
      return {3.6, 2.1, 1.3, 0.95, 0.78, 0.64, 0.53};
    case Transmission::kAutomatic:
      return {4.7, 3.1, 2.1, 1.67, 1.29, 1.0, 0.84, 0.67};
    default:
      return {1.0};
  }
}

void set_shift_timing(PowertrainParams& p, Transmission t, bool truck) {
  switch (t) {
    case Transmission::kManual:
      p.shift_ramp_down_s = 0.2, p.shift_open_s = 0.5, p.shift_ramp_up_s = 0.3;
      break;
    case Transmission::kAutomatedManual:
      p.shift_ramp_down_s = truck ? 0.3 : 0.15;
      p.shift_open_s = truck ? 0.6 : 0.3;
      p.shift_ramp_up_s = truck ? 0.4 : 0.2;
      break;
    case Transmission::kAutomatic:
      p.shift_ramp_down_s = 0.15, p.shift_open_s = 0.15, p.shift_ramp_up_s = 0.2;
      p.shift_min_scale = 0.4;
      break;
    case Transmission::kDualClutch:
      p.shift_ramp_down_s = 0.05, p.shift_open_s = 0.05, p.shift_ramp_up_s = 0.1;
      p.shift_min_scale = 0.6;
      break;
    case Transmission::kElectric:
      break;
  }
}

struct Geometry {
  double wheelbase_m, front_share;
};

Geometry draw_geometry(const ClassDefinition& c, RandomStream& rng, DrawnVehicle& d) {
  TrueVehicle& v = d.vehicle;
  d.electric = false;
  double mass = draw(rng, c.empty_mass_kg);
  v.wheelbase_m = draw(rng, c.wheelbase_m);
  v.track_m = draw(rng, c.track_m);
  const double front_share = draw(rng, c.front_weight_share);
  v.empty.cg_z_m = draw(rng, c.cg_height_m);
  d.payload_capacity_kg = draw(rng, c.payload_capacity_kg);
  v.drag_area_m2 = draw(rng, c.drag_area_m2);
  v.rolling_resistance_coeff = draw(rng, c.rolling_f0);
  v.rolling_resistance_speed_coeff_s2_per_m2 = draw(rng, c.rolling_f2_s2_per_m2);
  v.driveline_viscous_n_per_mps = draw(rng, c.driveline_viscous_n_per_mps);
  v.side_force_area_m2 = 0.8 * v.drag_area_m2 * rng.uniform(2.0, 3.0);
  v.wheel_radius_m = draw(rng, c.wheel_radius_m);
  v.steering_ratio = draw(rng, c.steering_ratio);
  v.empty.mass_kg = mass;
  v.empty.cg_x_m = v.wheelbase_m * (1.0 - front_share);
  v.empty.cg_y_m = 0.0;
  return {v.wheelbase_m, front_share};
}

void draw_powertrain(const ClassDefinition& c, RandomStream& rng, DrawnVehicle& d) {
  TrueVehicle& v = d.vehicle;
  PowertrainParams& p = v.powertrain;
  const CommonRanges& cr = common_ranges();
  const bool truck = c.id == VehicleClass::kHeavyTruck;
  p.transmission = pick(rng, c.transmissions);
  d.electric = p.transmission == Transmission::kElectric;
  if (d.electric) v.empty.mass_kg *= 1.0 + draw(rng, c.electric_extra_mass_fraction);
  v.driven_axle = pick(rng, c.driven_axles);
  const double scale = rng.uniform(0.95, 1.05);
  p.gear_ratios = gear_set(p.transmission, c.id, rng);
  for (double& r : p.gear_ratios) r *= scale;
  const double power_w = draw(rng, c.power_kw) * 1000.0;
  p.max_power_w = power_w;
  p.max_torque_nm = power_w / 1000.0 * rng.uniform(1.8, 2.6) * (truck ? 2.6 : 1.0);
  p.efficiency = rng.uniform(0.90, 0.95);
  p.prime_mover_inertia_kgm2 = draw(rng, c.engine_inertia_kgm2) * (d.electric ? 0.3 : 1.0);
  p.wheel_inertia_kgm2 = draw(rng, c.wheel_inertia_kgm2);
  p.torque_time_constant_s = d.electric
                                 ? rng.uniform(0.02, 0.05)
                                 : draw(rng, cr.torque_time_constant_s) * (truck ? 2.0 : 1.0);
  p.idle_speed_radps = (truck ? rng.uniform(550, 650) : rng.uniform(750, 850)) * kRpm;
  p.upshift_speed_radps = (truck ? rng.uniform(1500, 1800) : rng.uniform(2400, 3200)) * kRpm;
  p.downshift_speed_radps = (truck ? rng.uniform(900, 1100) : rng.uniform(1100, 1400)) * kRpm;
  // Final drive: top gear at cruising speed turns the prime mover at a chosen speed.
  const double cruise_mps = truck ? 23.6 : 36.1;
  const double top_rpm = d.electric ? rng.uniform(8000, 11000)
                                    : (truck ? rng.uniform(1100, 1300) : rng.uniform(2200, 2800));
  p.final_drive_ratio = top_rpm * kRpm / (cruise_mps / v.wheel_radius_m) / p.gear_ratios.back();
  set_shift_timing(p, p.transmission, truck);
  p.min_time_in_gear_s = truck ? 2.0 : 1.5;
  p.drag_torque_nm = power_w / 1000.0 * rng.uniform(0.12, 0.25);
  p.drag_torque_per_radps = power_w / 1000.0 * rng.uniform(2e-4, 4e-4);
  p.drag_report_error = draw(rng, cr.drag_report_error);
  p.accessory_power_w =
      rng.chance(0.6) ? draw(rng, cr.accessory_power_w) * (truck ? 2.0 : 1.0) : 0.0;
  p.accessory_on_s = rng.uniform(8.0, 20.0);
  p.accessory_off_s = rng.uniform(10.0, 30.0);
  p.accessory_phase_s = rng.uniform(0.0, 30.0);
  p.tc_stall_torque_ratio = draw(rng, cr.tc_stall_torque_ratio);
  p.tc_coupling_speed_ratio = draw(rng, cr.tc_coupling_speed_ratio);
  p.tc_stall_speed_radps = (truck ? rng.uniform(1300, 1700) : rng.uniform(1900, 2600)) * kRpm;
  p.tc_lockup_speed_mps = draw(rng, cr.tc_lockup_speed_mps);
  p.tc_model_error = draw(rng, cr.tc_model_error);
  const double weight_n = v.empty.mass_kg * kG;
  p.creep_wheel_torque_nm = draw(rng, cr.creep_force_per_weight) * weight_n * v.wheel_radius_m;
  p.regen_max_force_n = d.electric ? draw(rng, cr.regen_max_decel_g) * weight_n : 0.0;

  DrivelineParams& dl = v.driveline;
  dl.mode_frequency_first_gear_hz = draw(rng, c.mode_first_gear_hz);
  dl.mode_frequency_top_gear_hz = draw(rng, c.mode_top_gear_hz);
  dl.mode_damping_ratio = draw(rng, cr.mode_damping_ratio);
  dl.lag_s = draw(rng, cr.driveline_lag_s);
}

void draw_chassis(const ClassDefinition& c, RandomStream& rng, DrawnVehicle& d) {
  TrueVehicle& v = d.vehicle;
  const CommonRanges& cr = common_ranges();
  const bool truck = c.id == VehicleClass::kHeavyTruck;
  const double lf = v.empty.cg_x_m;
  const double lr = v.wheelbase_m - lf;
  v.empty.yaw_inertia_kgm2 = v.empty.mass_kg * lf * lr * rng.uniform(0.9, 1.15);
  d.max_mass_kg = v.empty.mass_kg + d.payload_capacity_kg;
  v.brake_gain_n_per_pa = d.max_mass_kg * kG / (draw(rng, c.brake_full_pressure_bar) * 1e5);
  v.brake_front_share = truck ? rng.uniform(0.40, 0.50) : rng.uniform(0.65, 0.75);
  v.roll_stiffness_front_share = rng.uniform(0.50, 0.65);
  v.load_transfer_time_constant_s = rng.uniform(0.06, 0.12);
  for (TyreParams* t : {&v.front_tyre, &v.rear_tyre}) {
    t->reference_load_n = c.tyre_reference_load_n;
    t->load_exponent = rng.uniform(0.7, 0.9);
    t->friction_coeff = rng.uniform(0.9, 1.1);
    t->relaxation_length_m = truck ? rng.uniform(0.6, 0.9) : rng.uniform(0.3, 0.5);
  }
  v.front_tyre.cornering_stiffness_per_load_per_rad = draw(rng, c.cornering_per_load_front);
  v.rear_tyre.cornering_stiffness_per_load_per_rad = draw(rng, c.cornering_per_load_rear);

  // Rear-right corner: the bump stop engages near the payload capacity (at about 60 % of it on
  // the rear axle), progressively above it.
  SuspensionParams& s = v.rear_right_suspension;
  s.stiffness_n_per_m = draw(rng, c.rear_wheel_rate_n_per_m);
  s.unsprung_mass_kg = truck ? rng.uniform(250, 350) : rng.uniform(35, 50);
  const StaticLoads empty = static_loads(v, v.empty);
  const double empty_sprung_n = empty.rear_right_n - s.unsprung_mass_kg * kG;
  const double z_empty = empty_sprung_n / s.stiffness_n_per_m;
  const double payload_stroke = 0.3 * d.payload_capacity_kg * kG / s.stiffness_n_per_m;
  s.knee_compression_m = z_empty + payload_stroke * rng.uniform(0.8, 1.1);
  s.progressive_rate_n_per_m2 = s.stiffness_n_per_m / 0.02 * rng.uniform(0.5, 1.5);
  s.damping_n_s_per_m = 2.0 * 0.3 * std::sqrt(s.stiffness_n_per_m * empty_sprung_n / kG);
  s.sensor_reference_m = z_empty - rng.uniform(0.01, 0.03);

  BrakeParams& b = v.brakes;
  b.pressure_offset_pa = draw(rng, cr.brake_pressure_offset_bar) * (truck ? 0.1 : 1.0) * 1e5;
  b.heat_capacity_j_per_k = v.empty.mass_kg * rng.uniform(5.0, 9.0);
  b.cooling_time_s = rng.uniform(200, 400);
  b.fade_start_c = rng.uniform(250, 350);
  b.fade_full_c = rng.uniform(500, 650);
  b.fade_max_fraction = draw(rng, cr.brake_fade_max_fraction);

  WheelSpeedParams& w = v.wheel_speed;
  w.radius_error_fraction = draw(rng, cr.speed_radius_error_fraction);
  w.slip_stiffness = truck ? rng.uniform(8, 12) : rng.uniform(12, 20);
  w.display_overread_fraction = draw(rng, cr.display_overread_fraction);
  w.display_offset_mps = rng.uniform(0.0, 0.3);
  v.rear_levelling = rng.chance(c.p_levelling);
  v.levelling_time_constant_s = rng.uniform(5.0, 15.0);
}

void draw_imu(const ClassDefinition& c, RandomStream& rng, DrawnVehicle& d) {
  ImuParams& m = d.vehicle.imu;
  const CommonRanges& cr = common_ranges();
  constexpr double kDegPerG = 3.14159265358979323846 / 180.0 / kG;
  constexpr double kDeg = 3.14159265358979323846 / 180.0;
  m.filter_cutoff_hz = draw(rng, cr.imu_filter_cutoff_hz);
  m.bias_x_mps2 = draw(rng, cr.imu_bias_mps2);
  m.bias_y_mps2 = draw(rng, cr.imu_bias_mps2);
  m.drift_mps2_per_sqrt_s = draw(rng, cr.imu_drift_mps2_per_sqrt_s);
  m.noise_std_mps2 = draw(rng, cr.imu_noise_std_mps2);
  m.gyro_bias_radps = rng.uniform(-0.003, 0.003);
  m.gyro_noise_std_radps = rng.uniform(0.001, 0.003);
  m.vibration_rms_mps2 = draw(rng, c.vibration_rms_mps2);
  m.vibration_frequency_hz = draw(rng, cr.imu_vibration_frequency_hz);
  m.vibration_q = rng.uniform(1.5, 3.0);
  m.engine_cylinders = d.electric ? 0 : (c.id == VehicleClass::kHeavyTruck ? 6 : 3 + rng.index(4));
  m.engine_vibration_mps2 = d.electric ? 0.0 : rng.uniform(0.01, 0.05);
  m.lever_forward_m = draw(rng, cr.imu_lever_forward_m);
  m.lever_left_m = draw(rng, cr.imu_lever_left_m);
  m.misalignment_yaw_rad = draw(rng, cr.imu_misalignment_deg) * kDeg;
  m.misalignment_pitch_rad = draw(rng, cr.imu_misalignment_deg) * kDeg;
  m.misalignment_roll_rad = draw(rng, cr.imu_misalignment_deg) * kDeg;
  m.pitch_per_accel_rad_per_mps2 = draw(rng, c.pitch_gradient_deg_per_g) * kDegPerG;
  m.roll_per_accel_rad_per_mps2 = draw(rng, c.roll_gradient_deg_per_g) * kDegPerG;
}

void draw_sensors(const ClassDefinition& c, RandomStream& rng, DrawnVehicle& d) {
  VehicleSensors& s = d.sensors;
  s.deflection = rng.chance(c.p_deflection_sensor);
  s.brake_pressure = rng.chance(c.p_brake_pressure);
  const bool engine_only = rng.chance(c.p_engine_torque_only);
  const bool per_axle = rng.chance(0.7);
  if (!d.electric && engine_only) {
    s.torque = TorqueSignal::kEngineTorque;
  } else if (d.vehicle.driven_axle == DrivenAxle::kAll && d.electric && per_axle) {
    s.torque = TorqueSignal::kPerAxle;
  } else {
    s.torque = TorqueSignal::kWheelTorque;
  }
  s.speed = rng.chance(c.p_display_speed_only) ? SpeedSignal::kDisplay : SpeedSignal::kEsc;
  s.lateral = !rng.chance(c.p_no_lateral);
}

double period(RandomStream& rng, std::initializer_list<double> choices) {
  const std::vector<double> v(choices);
  return v[static_cast<std::size_t>(rng.index(static_cast<int>(v.size())))];
}

void draw_can(RandomStream& rng, DrawnVehicle& d) {
  CanConventions& c = d.can;
  c.motorola = rng.chance(0.5);
  c.extended_ids = rng.chance(0.2);
  c.id_base = 0x100 + 0x10 * static_cast<std::uint32_t>(rng.index(32));
  c.accel_in_g = rng.chance(0.25);
  c.yaw_in_rad = rng.chance(0.2);
  c.yaw_positive_right = rng.chance(0.25);
  c.steering_positive_right = rng.chance(0.25);
  c.pressure_in_kpa = rng.chance(0.3);
  c.deflection_muxed = rng.chance(0.3);
  const Range& lat = common_ranges().ecu_latency_s;
  c.torque_period_s = period(rng, {0.01, 0.02});
  c.torque_latency_s = rng.uniform(0.005, 0.02);
  c.dynamics_period_s = period(rng, {0.01, 0.02});
  c.dynamics_latency_s = rng.uniform(0.01, lat.high);
  c.speed_period_s = period(rng, {0.01, 0.02});
  c.speed_latency_s = rng.uniform(0.01, 0.03);
  c.brake_period_s = period(rng, {0.01, 0.02});
  c.brake_latency_s = rng.uniform(0.005, 0.015);
  c.steering_period_s = 0.01;
  c.steering_latency_s = rng.uniform(0.005, 0.01);
  c.level_period_s = period(rng, {0.02, 0.05, 0.1});
  c.level_latency_s = rng.uniform(0.02, 0.1);
  c.display_period_s = period(rng, {0.1, 0.2});
  c.display_latency_s = rng.uniform(0.1, 0.3);
}

void draw_knowledge(RandomStream& rng, DrawnVehicle& d) {
  KnowledgeErrors& e = d.errors;
  e.cornering_front = rng.uniform(-0.2, 0.2);
  e.cornering_rear = rng.uniform(-0.2, 0.2);
  e.brake_gain = rng.uniform(-0.1, 0.1);
  e.rotating_mass = rng.uniform(-0.3, 0.3);
  e.suspension_stiffness = rng.uniform(-0.05, 0.05);
  e.drag_area = rng.uniform(-0.1, 0.1);
  e.rolling_coeff = rng.uniform(-0.25, 0.25);
  e.cg_position_m = rng.uniform(-0.01, 0.01) * d.vehicle.wheelbase_m;
  e.torque_scale = rng.uniform(-0.05, 0.05);
  e.wheel_radius = rng.uniform(-0.02, 0.02);
  e.declared_torque_accuracy = 0.05;
  e.declared_radius_accuracy = 0.02;
}

}  // namespace

TrueVehicle DrawnVehicle::true_vehicle(Realism realism) const {
  TrueVehicle v = vehicle;
  if (realism.has(Effect::kMassUncertainty)) {
    // The extra mass (fuel, options) sits at the empty CG.
    v.empty.yaw_inertia_kgm2 *= (v.empty.mass_kg + empty_mass_deviation_kg) / v.empty.mass_kg;
    v.empty.mass_kg += empty_mass_deviation_kg;
  }
  return v;
}

DrawnVehicle draw_vehicle(VehicleClass vehicle_class, std::uint64_t vehicle_seed) {
  const ClassDefinition& c = class_definition(vehicle_class);
  DrawnVehicle d;
  d.vehicle_class = vehicle_class;
  d.seed = vehicle_seed;
  d.id = std::string(vehicle_class_name(vehicle_class)) + "-" + std::to_string(vehicle_seed);
  const std::uint64_t base = d.stream_seed();
  RandomStream geometry(base, hash_name("population.geometry"));
  RandomStream powertrain(base, hash_name("population.powertrain"));
  RandomStream chassis(base, hash_name("population.chassis"));
  RandomStream imu(base, hash_name("population.imu"));
  RandomStream sensors(base, hash_name("population.sensors"));
  RandomStream can(base, hash_name("population.can"));
  RandomStream knowledge(base, hash_name("population.knowledge"));
  draw_geometry(c, geometry, d);
  draw_powertrain(c, powertrain, d);
  draw_chassis(c, chassis, d);
  draw_imu(c, imu, d);
  draw_sensors(c, sensors, d);
  draw_can(can, d);
  draw_knowledge(knowledge, d);
  d.empty_mass_deviation_kg =
      d.vehicle.empty.mass_kg * draw(geometry, common_ranges().empty_mass_deviation_fraction);
  return d;
}

std::vector<DrawnVehicle> draw_population(int count, std::uint64_t first_seed) {
  std::vector<DrawnVehicle> out;
  for (int i = 0; i < count; ++i) {
    const auto c = static_cast<VehicleClass>(i % kVehicleClassCount);
    out.push_back(draw_vehicle(c, first_seed + static_cast<std::uint64_t>(i)));
  }
  return out;
}

bool parse_vehicle_id(const std::string& id, DrawnVehicle* out, std::string* error) {
  const auto dash = id.rfind('-');
  if (dash == std::string::npos || dash == 0 || dash + 1 == id.size()) {
    *error = "vehicle id '" + id + "' is not <class>-<seed>";
    return false;
  }
  const std::string class_text = id.substr(0, dash);
  const bool tractor = class_text == kTractorIdPrefix;
  const auto c = parse_vehicle_class(class_text);
  if (!c && !tractor) {
    *error = "vehicle id '" + id + "': unknown class '" + class_text + "'";
    return false;
  }
  const std::string seed_text = id.substr(dash + 1);
  if (seed_text.find_first_not_of("0123456789") != std::string::npos || seed_text.size() > 18) {
    *error = "vehicle id '" + id + "': the seed must be a non-negative integer";
    return false;
  }
  const std::uint64_t seed = std::stoull(seed_text);
  *out = tractor ? draw_tractor(seed) : draw_vehicle(*c, seed);
  return true;
}

bool bus_has_engine_speed(const DrawnVehicle& v) {
  return v.sensors.torque == TorqueSignal::kEngineTorque ||
         (v.vehicle_class == VehicleClass::kHeavyTruck && !v.electric);
}

std::string describe_vehicle(const DrawnVehicle& d) {
  const TrueVehicle& v = d.vehicle;
  char buf[512];
  const char* torque = d.sensors.torque == TorqueSignal::kEngineTorque ? "engine-torque"
                       : d.sensors.torque == TorqueSignal::kPerAxle    ? "torque-per-axle"
                                                                       : "wheel-torque";
  std::snprintf(buf, sizeof buf,
                "%s: %.0f kg empty (+%.0f kg payload max), l %.2f m, %s %s %zu-speed, %s%s%s%s%s",
                d.id.c_str(), v.empty.mass_kg, d.payload_capacity_kg, v.wheelbase_m,
                std::string(driven_axle_name(v.driven_axle)).c_str(),
                std::string(transmission_name(v.powertrain.transmission)).c_str(),
                v.powertrain.gear_ratios.size(), torque,
                d.sensors.deflection ? ", deflection" : ", no deflection",
                d.sensors.brake_pressure ? "" : ", no brake pressure",
                d.sensors.speed == SpeedSignal::kDisplay ? ", display speed" : "",
                v.rear_levelling ? ", levelled rear" : "");
  return buf;
}

std::string population_rules_text() {
  return "rules v1: gear sets (manual 5/6, AMT 5, DCT 7, AT 8, truck AMT 12, truck AT 6, "
         "electric 1) scaled U(0.95,1.05); final drive for 2200-2800 rpm at 130 km/h (truck "
         "1100-1300 rpm at 85 km/h, electric 8000-11000 rpm); torque/power 1.8-2.6 Nm/kW "
         "(truck x2.6); A/C present 60 %; creep from creep_force_per_weight; bump stop at "
         "0.8-1.1 x the stroke of 30 % of the payload capacity on the rear-right corner; "
         "brake gain for 1 g at GVW; conventions: Motorola 50 %, 29-bit 20 %, a in g 25 %, "
         "yaw in rad/s 20 %, yaw positive right 25 %, steering positive right 25 %, pressure "
         "in kPa 30 %, muxed level 30 %; per-axle torque "
         "70 % of electric AWD; engine speed on every combustion truck's bus; knowledge errors "
         "C_alpha +-20 %, K_brake +-10 %, m_rot "
         "+-30 %, c +-5 %, CdA +-10 %, f0 +-25 %, l_f +-1 % l; datasheet scale: torque +-5 %, "
         "radius +-2 %\n";
}

}  // namespace vmass::sim

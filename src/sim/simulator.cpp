#include "vmass/sim/simulator.hpp"

#include <algorithm>
#include <cmath>

#include "vmass/sim/driveline.hpp"
#include "vmass/sim/driver.hpp"
#include "vmass/sim/imu_model.hpp"
#include "vmass/sim/powertrain.hpp"
#include "vmass/sim/suspension.hpp"
#include "vmass/sim/vehicle_model.hpp"
#include "vmass/sim/wind.hpp"

namespace vmass::sim {

namespace {

constexpr double kDisplayMinSpeedMps = 0.3;
constexpr double kBrakeLightPressurePa = 2.0e4;  // about the pedal free travel

// Quasi-static longitudinal slip of each axle's tyres (0 without the wheel_speed effect).
struct AxleSlips {
  double front = 0.0;
  double rear = 0.0;
};

// One run of simulate(): the models, their states and the stepping (see simulator.hpp).
class SimulationRun {
 public:
  SimulationRun(const Scenario& scenario, const SimulationOptions& options, SimulationResult* out)
      : sc_(scenario),
        vp_(scenario.vehicle),
        fx_(options.realism),
        res_(*out),
        model_(vp_, scenario.road, fx_),
        pt_(vp_.powertrain, vp_.wheel_radius_m, fx_),
        driveline_(vp_.driveline, vp_.powertrain, 1.0 / scenario.integration_rate_hz, fx_),
        driver_(driver_params(scenario, fx_), scenario.driver, vp_),
        sensors_(options.ideal_sensors ? SensorSpec::ideal() : scenario.sensors,
                 options.noise.value_or(scenario.default_noise), options.seed, vp_.wheel_radius_m),
        imu_(vp_.imu, scenario.integration_rate_hz, vp_.gravity_mps2, options.seed, fx_),
        wind_(scenario.wind, options.seed),
        record_trace_(options.record_ecu_trace),
        fine_(fx_.any() || options.record_ecu_trace) {}

  void run();

 private:
  static DriverParams driver_params(const Scenario& s, Realism fx);
  void start();
  void advance(double t_s, double dt_s);
  EcuSignals ecu_signals(TimeUs t_us, const VehicleOutputs& o);
  AxleSlips axle_slips(const VehicleOutputs& o) const;
  double speed_signal(const VehicleOutputs& o) const;
  void update_driven_slip(const VehicleOutputs& o, double dt_s);
  double deflection_reading() const;
  void record_tick(TimeUs t_us, const VehicleOutputs& o, const EcuSignals& ecu);

  const Scenario& sc_;
  const TrueVehicle& vp_;
  Realism fx_;
  SimulationResult& res_;
  VehicleModel model_;
  Powertrain pt_;
  Driveline driveline_;
  Driver driver_;
  SensorModel sensors_;
  ImuModel imu_;
  Wind wind_;
  bool record_trace_;
  bool fine_;  ///< evaluate the ECU signals at every integration step, not only at ticks

  VehicleState state_;
  VehicleInputs in_;
  DriverCommand cmd_;
  double brake_temperature_c_ = 0.0;
  double levelling_m_ = 0.0;      ///< self-levelling's offset of the sensor reading
  double empty_reading_m_ = 0.0;  ///< the sensor's reading of the empty car, level
};

DriverParams SimulationRun::driver_params(const Scenario& s, Realism fx) {
  DriverParams p = s.driver_params;
  const PowertrainParams& pt = s.vehicle.powertrain;
  if (fx.has(Effect::kRegenBraking) && pt.transmission == Transmission::kElectric) {
    p.regen_max_force_n = pt.regen_max_force_n;
    p.regen_min_speed_mps = pt.regen_min_speed_mps;
  }
  return p;
}

void SimulationRun::start() {
  in_.mass = res_.initial_mass;
  const double v0 = sc_.initial_speed_mps;
  double cruise_torque = 0.0;
  if (v0 > 0.0) {
    cruise_torque = (0.5 * vp_.air_density_kg_per_m3 * vp_.drag_area_m2 * v0 * v0 +
                     vp_.rolling_resistance_coeff * in_.mass.mass_kg * vp_.gravity_mps2) *
                    vp_.wheel_radius_m;
  }
  state_ = model_.settled_state(in_, v0);
  pt_.reset(v0, cruise_torque);
  driveline_.reset(pt_.wheel_torque_nm());
  driver_.reset(0.0, state_);
  cmd_ = driver_.update(0.0, 0.0, state_);
  in_.wheel_torque_nm = driveline_.hub_torque_nm();
  in_.rotating_mass_kg = pt_.rotating_mass_kg();
  in_.brake_pressure_pa = cmd_.brake_pressure_pa;
  in_.road_wheel_angle_rad = cmd_.steering_wheel_angle_rad / vp_.steering_ratio;
  in_.wind_head_mps = fx_.has(Effect::kWind) ? wind_.head_mps() : 0.0;
  in_.wind_cross_mps = fx_.has(Effect::kWind) ? wind_.cross_mps() : 0.0;
  brake_temperature_c_ = vp_.brakes.ambient_c;
  update_driven_slip(model_.evaluate(state_, in_), 0.0);  // the starting slip, without a rate

  const SuspensionParams& sp = vp_.rear_right_suspension;
  const StaticLoads empty = static_loads(vp_, vp_.empty);
  empty_reading_m_ =
      spring_compression(sp, empty.rear_right_n - sp.unsprung_mass_kg * vp_.gravity_mps2) -
      sp.sensor_reference_m;
  // A levelled car has already brought its ride height back before the drive starts.
  levelling_m_ = vp_.rear_levelling
                     ? state_.susp_compression_m - sp.sensor_reference_m - empty_reading_m_
                     : 0.0;
}

void SimulationRun::advance(double t_s, double dt_s) {
  in_.mass = sc_.mass_at(t_s);
  cmd_ = driver_.update(t_s, dt_s, state_);
  pt_.step(t_s, dt_s, cmd_.wheel_torque_demand_nm, state_.vx_mps, cmd_.brake_pressure_pa > 1e4);
  in_.wheel_torque_nm = driveline_.step(pt_.wheel_torque_nm(), pt_.gear_signal());
  in_.rotating_mass_kg = pt_.rotating_mass_kg();
  in_.brake_pressure_pa = cmd_.brake_pressure_pa;
  in_.road_wheel_angle_rad = cmd_.steering_wheel_angle_rad / vp_.steering_ratio;
  if (fx_.has(Effect::kWind)) {
    wind_.step(dt_s);
    in_.wind_head_mps = wind_.head_mps();
    in_.wind_cross_mps = wind_.cross_mps();
  }
  if (fx_.has(Effect::kBrakeFade)) {
    const BrakeParams& b = vp_.brakes;
    const double power_w = vp_.brake_gain_n_per_pa * in_.brake_gain_scale *
                           std::max(0.0, in_.brake_pressure_pa) * std::max(0.0, state_.vx_mps);
    brake_temperature_c_ += dt_s * (power_w / b.heat_capacity_j_per_k -
                                    (brake_temperature_c_ - b.ambient_c) / b.cooling_time_s);
    in_.brake_gain_scale = b.gain_scale(brake_temperature_c_);
  }
  if (vp_.rear_levelling) {
    const double raw = state_.susp_compression_m - vp_.rear_right_suspension.sensor_reference_m;
    levelling_m_ += dt_s * (raw - empty_reading_m_ - levelling_m_) / vp_.levelling_time_constant_s;
  }
  model_.step(state_, in_, dt_s);
}

AxleSlips SimulationRun::axle_slips(const VehicleOutputs& o) const {
  if (!fx_.has(Effect::kWheelSpeed) || state_.stopped) return {};
  const double front_drive = front_drive_share(vp_.driven_axle);
  const double fx_front = front_drive * o.drive_force_n - vp_.brake_front_share * o.brake_force_n;
  const double fx_rear =
      (1.0 - front_drive) * o.drive_force_n - (1.0 - vp_.brake_front_share) * o.brake_force_n;
  const double c = vp_.wheel_speed.slip_stiffness;
  return {fx_front / (c * std::max(o.front_axle_load_n, 1.0)),
          fx_rear / (c * std::max(o.rear_axle_load_n, 1.0))};
}

// Mean longitudinal slip of the four wheels times the speed, as the ESC averages them.
double SimulationRun::speed_signal(const VehicleOutputs& o) const {
  const double v = state_.vx_mps;
  if (!fx_.has(Effect::kWheelSpeed) || state_.stopped) return v;
  const AxleSlips k = axle_slips(o);
  return v * (1.0 + vp_.wheel_speed.radius_error_fraction) * (1.0 + 0.5 * (k.front + k.rear));
}

// The driveline turns with the driven wheels: their slip, and its rate over the last step, go
// into the rotating parts' inertia (VehicleModel).
void SimulationRun::update_driven_slip(const VehicleOutputs& o, double dt_s) {
  const AxleSlips k = axle_slips(o);
  const double front_drive = front_drive_share(vp_.driven_axle);
  const double slip = front_drive * k.front + (1.0 - front_drive) * k.rear;
  in_.driven_slip_rate_per_s = dt_s > 0.0 ? (slip - in_.driven_slip) / dt_s : 0.0;
  in_.driven_slip = slip;
}

double SimulationRun::deflection_reading() const {
  return state_.susp_compression_m - vp_.rear_right_suspension.sensor_reference_m - levelling_m_;
}

EcuSignals SimulationRun::ecu_signals(TimeUs t_us, const VehicleOutputs& o) {
  EcuSignals e;
  e.time_us = t_us;
  e.wheel_torque_nm = pt_.reported_wheel_torque_nm();
  e.engine_torque_nm = pt_.reported_engine_torque_nm();
  e.engine_speed_radps = pt_.engine_speed_radps();
  e.gear = pt_.gear_signal();
  e.brake_pressure_pa = cmd_.brake_pressure_pa +
                        (fx_.has(Effect::kBrakeSensor) ? vp_.brakes.pressure_offset_pa : 0.0);
  // The switch sits on the pedal: it sees the driver's pressure, not the sensor's offset.
  e.brake_light = cmd_.brake_pressure_pa > kBrakeLightPressurePa;
  ImuInput imu;
  imu.specific_force_x_mps2 = o.specific_force_x_mps2;
  imu.specific_force_y_mps2 = o.specific_force_y_mps2;
  imu.yaw_rate_radps = state_.yaw_rate_radps;
  imu.yaw_accel_radps2 = o.yaw_accel_radps2;
  imu.body_accel_x_mps2 = state_.load_accel_x_mps2 - vp_.gravity_mps2 * std::sin(o.grade_rad);
  imu.body_accel_y_mps2 =
      state_.load_accel_y_mps2 - vp_.gravity_mps2 * std::cos(o.grade_rad) * std::sin(o.bank_rad);
  imu.speed_mps = state_.vx_mps;
  imu.roughness = fx_.has(Effect::kRoadRoughness) ? sc_.road.roughness(state_.distance_m) : 0.0;
  imu.engine_speed_radps = e.engine_speed_radps;
  imu.cg_shift_forward_m = vp_.empty.cg_x_m - in_.mass.cg_x_m;
  imu.cg_shift_left_m = in_.mass.cg_y_m - vp_.empty.cg_y_m;
  const ImuOutput imu_out = imu_.step(imu);
  e.accel_x_mps2 = imu_out.accel_x_mps2;
  e.accel_y_mps2 = imu_out.accel_y_mps2;
  e.yaw_rate_radps = imu_out.yaw_rate_radps;
  e.speed_mps = speed_signal(o);
  const WheelSpeedParams& w = vp_.wheel_speed;
  e.display_speed_mps =
      e.speed_mps > kDisplayMinSpeedMps
          ? e.speed_mps * (1.0 + w.display_overread_fraction) + w.display_offset_mps
          : 0.0;
  e.steering_wheel_angle_rad = cmd_.steering_wheel_angle_rad;
  e.rear_right_deflection_m = deflection_reading();
  return e;
}

void SimulationRun::record_tick(TimeUs t_us, const VehicleOutputs& o, const EcuSignals& ecu) {
  TrueSignals ts;
  ts.wheel_torque_nm = ecu.wheel_torque_nm;
  ts.brake_pressure_pa = ecu.brake_pressure_pa;
  ts.accel_x_mps2 = ecu.accel_x_mps2;
  ts.accel_y_mps2 = ecu.accel_y_mps2;
  ts.yaw_rate_radps = ecu.yaw_rate_radps;
  ts.speed_mps = ecu.speed_mps;
  ts.steering_wheel_angle_rad = ecu.steering_wheel_angle_rad;
  ts.rear_right_deflection_m = ecu.rear_right_deflection_m;
  ts.gear = ecu.gear;
  res_.samples.push_back(sensors_.measure(t_us, ts));

  TruthRow r;
  r.time_us = t_us;
  r.mass_kg = in_.mass.mass_kg;
  r.speed_mps = state_.vx_mps;
  r.grade_rad = o.grade_rad;
  r.lateral_velocity_mps = state_.vy_mps;
  r.yaw_rate_radps = state_.yaw_rate_radps;
  r.accel_x_mps2 = o.specific_force_x_mps2;
  r.accel_y_mps2 = o.specific_force_y_mps2;
  r.wheel_torque_nm = pt_.reported_wheel_torque_nm();
  r.hub_torque_nm = in_.wheel_torque_nm;
  r.brake_pressure_pa = in_.brake_pressure_pa;
  r.brake_force_n = o.brake_force_n;
  r.drag_force_n = o.drag_force_n;
  r.rolling_resistance_n = o.rolling_resistance_n;
  r.rotating_mass_kg = in_.rotating_mass_kg;
  r.driven_slip = in_.driven_slip;
  r.driven_slip_rate_per_s = in_.driven_slip_rate_per_s;
  r.gear = pt_.gear_signal();
  r.steering_wheel_angle_rad = cmd_.steering_wheel_angle_rad;
  r.road_wheel_angle_rad = in_.road_wheel_angle_rad;
  r.bank_rad = o.bank_rad;
  r.long_accel_mps2 = o.dvx_dt_mps2;
  r.x_m = state_.x_m;
  r.y_m = state_.y_m;
  r.yaw_rad = state_.yaw_rad;
  r.distance_m = state_.distance_m;
  r.cg_x_m = in_.mass.cg_x_m;
  r.cg_y_m = in_.mass.cg_y_m;
  r.front_axle_load_n = o.front_axle_load_n;
  r.rear_axle_load_n = o.rear_axle_load_n;
  r.rear_right_load_n = o.rear_right_load_n;
  r.rear_right_deflection_m =
      state_.susp_compression_m - vp_.rear_right_suspension.sensor_reference_m;
  r.lateral_force_front_n = o.lateral_force_front_n;
  r.lateral_force_rear_n = o.lateral_force_rear_n;
  r.slip_front_rad = state_.slip_front_rad;
  r.slip_rear_rad = state_.slip_rear_rad;
  r.wheel_force_noise_n = sensors_.last_wheel_force_noise_n();
  r.stopped = state_.stopped;
  r.converter_ratio = pt_.converter_ratio();
  r.engine_speed_radps = pt_.engine_speed_radps();
  r.accessory_on = pt_.accessory_on();
  r.wind_head_mps = in_.wind_head_mps;
  r.wind_cross_mps = in_.wind_cross_mps;
  r.esc_brake_force_n = o.esc_brake_force_n;
  r.abs_active = o.abs_active;
  r.bump_force_n = o.bump_force_n;
  r.viscous_loss_n = o.viscous_loss_n;
  r.brake_temperature_c = brake_temperature_c_;
  r.brake_gain_scale = in_.brake_gain_scale;
  res_.truth.push_back(r);
}

void SimulationRun::run() {
  const double tick_hz = sc_.tick_rate_hz;
  const long substeps = std::lround(sc_.integration_rate_hz / tick_hz);
  const double dt = 1.0 / (tick_hz * static_cast<double>(substeps));
  const long ticks = static_cast<long>(std::floor(sc_.duration_s * tick_hz + 1e-9)) + 1;
  res_.samples.reserve(static_cast<std::size_t>(ticks));
  res_.truth.reserve(static_cast<std::size_t>(ticks));
  if (record_trace_) {
    res_.ecu_trace_rate_hz = sc_.integration_rate_hz;
    res_.ecu_trace.reserve(static_cast<std::size_t>(ticks * substeps));
  }
  start();
  for (long k = 0; k < ticks; ++k) {
    const double t_tick = static_cast<double>(k) / tick_hz;
    const long steps = (k + 1 == ticks) ? 1 : substeps;
    for (long j = 0; j < steps; ++j) {
      const double t = t_tick + static_cast<double>(j) * dt;
      if (j == 0 || fine_) {
        in_.mass = sc_.mass_at(t);
        const VehicleOutputs o = model_.evaluate(state_, in_);
        const EcuSignals ecu = ecu_signals(from_seconds(t), o);
        if (record_trace_) res_.ecu_trace.push_back(ecu);
        if (j == 0) record_tick(from_seconds(t_tick), o, ecu);
        update_driven_slip(o, fine_ ? dt : 1.0 / tick_hz);  // for the steps that follow
      }
      if (k + 1 == ticks) break;
      advance(t, dt);
    }
  }
}

}  // namespace

std::string simulate(const Scenario& scenario, const SimulationOptions& options,
                     SimulationResult* out) {
  if (out == nullptr) return "simulate: no result to fill";
  if (auto m = scenario.validate(); !m.empty()) return "scenario " + scenario.name + ": " + m;
  SimulationResult& res = *out;
  res = SimulationResult{};
  res.scenario = scenario.name;
  res.seed = options.seed;
  res.noise = options.noise.value_or(scenario.default_noise);
  res.vehicle = scenario.vehicle;
  res.sensors = options.ideal_sensors ? SensorSpec::ideal() : scenario.sensors;
  res.initial_mass = scenario.mass_at(0.0);
  res.tick_rate_hz = scenario.tick_rate_hz;
  res.realism = options.realism;
  SimulationRun(scenario, options, out).run();
  return "";
}

}  // namespace vmass::sim

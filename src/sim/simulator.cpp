#include "vmass/sim/simulator.hpp"

#include <cmath>

#include "vmass/sim/driver.hpp"
#include "vmass/sim/powertrain.hpp"
#include "vmass/sim/vehicle_model.hpp"

namespace vmass::sim {

namespace {

TruthRow make_truth(TimeUs t_us, const VehicleState& s, const VehicleInputs& in,
                    const VehicleOutputs& o, const Powertrain& pt, double steering_wheel_rad,
                    const SuspensionParams& susp, double eps_n) {
  TruthRow r;
  r.time_us = t_us;
  r.mass_kg = in.mass.mass_kg;
  r.speed_mps = s.vx_mps;
  r.grade_rad = o.grade_rad;
  r.lateral_velocity_mps = s.vy_mps;
  r.yaw_rate_radps = s.yaw_rate_radps;
  r.accel_x_mps2 = o.specific_force_x_mps2;
  r.accel_y_mps2 = o.specific_force_y_mps2;
  r.wheel_torque_nm = in.wheel_torque_nm;
  r.brake_pressure_pa = in.brake_pressure_pa;
  r.brake_force_n = o.brake_force_n;
  r.drag_force_n = o.drag_force_n;
  r.rolling_resistance_n = o.rolling_resistance_n;
  r.rotating_mass_kg = in.rotating_mass_kg;
  r.gear = pt.gear_signal();
  r.steering_wheel_angle_rad = steering_wheel_rad;
  r.road_wheel_angle_rad = in.road_wheel_angle_rad;
  r.bank_rad = o.bank_rad;
  r.long_accel_mps2 = o.dvx_dt_mps2;
  r.x_m = s.x_m;
  r.y_m = s.y_m;
  r.yaw_rad = s.yaw_rad;
  r.distance_m = s.distance_m;
  r.cg_x_m = in.mass.cg_x_m;
  r.cg_y_m = in.mass.cg_y_m;
  r.front_axle_load_n = o.front_axle_load_n;
  r.rear_axle_load_n = o.rear_axle_load_n;
  r.rear_right_load_n = o.rear_right_load_n;
  r.rear_right_deflection_m = s.susp_compression_m - susp.sensor_reference_m;
  r.lateral_force_front_n = o.lateral_force_front_n;
  r.lateral_force_rear_n = o.lateral_force_rear_n;
  r.slip_front_rad = s.slip_front_rad;
  r.slip_rear_rad = s.slip_rear_rad;
  r.wheel_force_noise_n = eps_n;
  r.stopped = s.stopped;
  return r;
}

}  // namespace

std::string simulate(const Scenario& scenario, const SimulationOptions& options,
                     SimulationResult* out) {
  if (out == nullptr) return "simulate: no result to fill";
  if (auto m = scenario.validate(); !m.empty()) return "scenario " + scenario.name + ": " + m;

  const TrueVehicle& vp = scenario.vehicle;
  const double tick_hz = scenario.tick_rate_hz;
  const long substeps = std::lround(scenario.integration_rate_hz / tick_hz);
  const double dt = 1.0 / (tick_hz * static_cast<double>(substeps));
  const long ticks = static_cast<long>(std::floor(scenario.duration_s * tick_hz + 1e-9)) + 1;

  SimulationResult& res = *out;
  res = SimulationResult{};
  res.scenario = scenario.name;
  res.seed = options.seed;
  res.noise = options.noise.value_or(scenario.default_noise);
  res.vehicle = vp;
  res.sensors = options.ideal_sensors ? SensorSpec::ideal() : scenario.sensors;
  res.initial_mass = scenario.mass_at(0.0);
  res.tick_rate_hz = tick_hz;
  res.samples.reserve(static_cast<std::size_t>(ticks));
  res.truth.reserve(static_cast<std::size_t>(ticks));

  const VehicleModel model(vp, scenario.road);
  Powertrain pt(vp.powertrain, vp.wheel_radius_m);
  Driver driver(scenario.driver_params, scenario.driver, vp);
  SensorModel sensors(res.sensors, res.noise, options.seed, vp.wheel_radius_m);

  VehicleInputs in;
  in.mass = res.initial_mass;
  const double v0 = scenario.initial_speed_mps;
  double cruise_torque = 0.0;
  if (v0 > 0.0) {
    cruise_torque = (0.5 * vp.air_density_kg_per_m3 * vp.drag_area_m2 * v0 * v0 +
                     vp.rolling_resistance_coeff * in.mass.mass_kg * vp.gravity_mps2) *
                    vp.wheel_radius_m;
  }
  VehicleState state = model.settled_state(in, v0);
  pt.reset(v0, cruise_torque);
  driver.reset(0.0, state);
  DriverCommand cmd = driver.update(0.0, 0.0, state);
  in.wheel_torque_nm = pt.wheel_torque_nm();
  in.rotating_mass_kg = pt.rotating_mass_kg();
  in.brake_pressure_pa = cmd.brake_pressure_pa;
  in.road_wheel_angle_rad = cmd.steering_wheel_angle_rad / vp.steering_ratio;

  for (long k = 0; k < ticks; ++k) {
    const double t = static_cast<double>(k) / tick_hz;
    const TimeUs t_us = from_seconds(t);
    const VehicleOutputs o = model.evaluate(state, in);
    TrueSignals ts;
    ts.wheel_torque_nm = in.wheel_torque_nm;
    ts.brake_pressure_pa = in.brake_pressure_pa;
    ts.accel_x_mps2 = o.specific_force_x_mps2;
    ts.accel_y_mps2 = o.specific_force_y_mps2;
    ts.yaw_rate_radps = state.yaw_rate_radps;
    ts.speed_mps = state.vx_mps;
    ts.steering_wheel_angle_rad = cmd.steering_wheel_angle_rad;
    ts.rear_right_deflection_m =
        state.susp_compression_m - vp.rear_right_suspension.sensor_reference_m;
    ts.gear = pt.gear_signal();
    res.samples.push_back(sensors.measure(t_us, ts));
    res.truth.push_back(make_truth(t_us, state, in, o, pt, cmd.steering_wheel_angle_rad,
                                   vp.rear_right_suspension, sensors.last_wheel_force_noise_n()));
    if (k + 1 == ticks) break;

    for (long j = 0; j < substeps; ++j) {
      const double ts_sub = t + static_cast<double>(j) * dt;
      in.mass = scenario.mass_at(ts_sub);
      cmd = driver.update(ts_sub, dt, state);
      pt.step(dt, cmd.wheel_torque_demand_nm, state.vx_mps);
      in.wheel_torque_nm = pt.wheel_torque_nm();
      in.rotating_mass_kg = pt.rotating_mass_kg();
      in.brake_pressure_pa = cmd.brake_pressure_pa;
      in.road_wheel_angle_rad = cmd.steering_wheel_angle_rad / vp.steering_ratio;
      model.step(state, in, dt);
    }
    in.mass = scenario.mass_at(static_cast<double>(k + 1) / tick_hz);
  }
  return "";
}

}  // namespace vmass::sim

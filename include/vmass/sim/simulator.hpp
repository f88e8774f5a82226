// simulate(): runs a Scenario. The car (VehicleModel), its powertrain, driveline and the driver
// are integrated with RK4 at integration_rate_hz (1 kHz). At every integration step the signals
// as the ECUs see them (EcuSignals: the ECU's reported torque, the IMU's output, the wheel-speed
// based speed, ...) are computed and, with record_ecu_trace, kept: the vehicle population's CAN
// writer samples them at each message's own cycle time and latency (bus_timing). At
// tick_rate_hz (100 Hz) the SensorModel reads the current EcuSignals into a Sample and the
// hidden true state goes into a TruthRow. Sample k and TruthRow k describe time
// k / tick_rate_hz, from 0 to duration_s inclusive.
//
// options.realism switches the real-world effects (realism.hpp); with none, EcuSignals are the
// true values and the result is the demo simulator's.
//
// Deterministic: the same scenario, options and seed give bit-identical results (randomness
// comes only from seeded streams). A 200 s scenario takes well under a second.
//
// Pure function of its arguments; thread-safe (no shared state).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "vmass/core/sample.hpp"
#include "vmass/sim/realism.hpp"
#include "vmass/sim/scenario.hpp"

namespace vmass::sim {

struct SimulationOptions {
  std::uint64_t seed = 1;
  std::optional<NoiseSet> noise;  ///< wheel-force noise set; default: the scenario's
  bool ideal_sensors = false;     ///< no sensor noise, bias or quantisation at all
  Realism realism = Realism::none();
  bool record_ecu_trace = false;  ///< keep EcuSignals at every integration step
};

/// The signals as the ECUs read them, before each transmitted sample's noise and quantisation,
/// in the Sample's units and frame (see the header comment; the effects decide how far they are
/// from the truth).
struct EcuSignals {
  TimeUs time_us = 0;
  double wheel_torque_nm = 0.0;   ///< the ECU's reported wheel torque
  double engine_torque_nm = 0.0;  ///< the ECU's reported engine (motor) torque
  double engine_speed_radps = 0.0;
  int gear = 0;
  double brake_pressure_pa = 0.0;  ///< as the sensor reads it (offset included)
  bool brake_light = false;        ///< the pedal switch: on from the first bar of true pressure
  double accel_x_mps2 = 0.0;       ///< IMU output
  double accel_y_mps2 = 0.0;
  double yaw_rate_radps = 0.0;
  double speed_mps = 0.0;          ///< the ESC's speed from the wheels
  double display_speed_mps = 0.0;  ///< the instrument cluster's speed
  double steering_wheel_angle_rad = 0.0;
  double rear_right_deflection_m = 0.0;  ///< sensor reading (levelling included)
};

/// The hidden truth at one tick. Accelerations are specific forces in the body frame (what a
/// perfect accelerometer would read), speeds and rates in the ISO 8855 body frame.
struct TruthRow {
  TimeUs time_us = 0;
  double mass_kg = 0.0;
  double speed_mps = 0.0;  ///< v_x
  double grade_rad = 0.0;
  double lateral_velocity_mps = 0.0;  ///< v_y at the centre of gravity
  double yaw_rate_radps = 0.0;
  double accel_x_mps2 = 0.0;  ///< specific force
  double accel_y_mps2 = 0.0;
  double wheel_torque_nm = 0.0;  ///< the ECU's reported wheel torque (before noise)
  double hub_torque_nm = 0.0;    ///< the torque that drives the car (after the driveline)
  double brake_pressure_pa = 0.0;
  double brake_force_n = 0.0;  ///< applied (0 at rest; K_brake P when moving)
  double drag_force_n = 0.0;
  double rolling_resistance_n = 0.0;
  double rotating_mass_kg = 0.0;  ///< m_rot in effect
  double driven_slip = 0.0;       ///< the driven wheels' slip: the driveline turns at v (1 + it)
  double driven_slip_rate_per_s = 0.0;
  int gear = 0;  ///< engaged gear, 0 while the clutch is open
  double steering_wheel_angle_rad = 0.0;
  double road_wheel_angle_rad = 0.0;
  double bank_rad = 0.0;
  double long_accel_mps2 = 0.0;  ///< dv_x/dt (kinematic, not specific force)
  double x_m = 0.0;
  double y_m = 0.0;
  double yaw_rad = 0.0;
  double distance_m = 0.0;
  double cg_x_m = 0.0;  ///< l_f of the loaded car
  double cg_y_m = 0.0;
  double front_axle_load_n = 0.0;
  double rear_axle_load_n = 0.0;
  double rear_right_load_n = 0.0;
  double rear_right_deflection_m = 0.0;  ///< what the sensor would read without noise/offset
  double lateral_force_front_n = 0.0;    ///< ISO sign
  double lateral_force_rear_n = 0.0;
  double slip_front_rad = 0.0;  ///< ISO slip angle (positive: force to the right)
  double slip_rear_rad = 0.0;
  double wheel_force_noise_n = 0.0;  ///< eps added to the wheel-force signal at this tick
  bool stopped = false;
  // Realism effects' states (0 when off).
  double converter_ratio = 1.0;
  double engine_speed_radps = 0.0;
  bool accessory_on = false;
  double wind_head_mps = 0.0;
  double wind_cross_mps = 0.0;
  double esc_brake_force_n = 0.0;
  bool abs_active = false;
  double bump_force_n = 0.0;
  double viscous_loss_n = 0.0;
  double brake_temperature_c = 0.0;
  double brake_gain_scale = 1.0;
};

struct SimulationResult {
  std::string scenario;
  std::uint64_t seed = 0;
  NoiseSet noise = NoiseSet::kNone;
  TrueVehicle vehicle;
  SensorSpec sensors;  ///< as applied (ideal() when ideal_sensors)
  MassProperties initial_mass;
  double tick_rate_hz = 100.0;
  Realism realism = Realism::none();
  std::vector<Sample> samples;
  std::vector<TruthRow> truth;
  double ecu_trace_rate_hz = 0.0;     ///< integration rate when recorded
  std::vector<EcuSignals> ecu_trace;  ///< every integration step, when recorded
};

/// Runs the scenario. Returns "" and fills *out, or a message (invalid scenario or options).
std::string simulate(const Scenario& scenario, const SimulationOptions& options,
                     SimulationResult* out);

}  // namespace vmass::sim

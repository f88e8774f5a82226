// The demo vehicle's CAN bus: its DBC, the frames its ECUs would send for a simulated drive,
// and the config's `can:` section that maps the DBC signals back to the estimator inputs (the
// demo team, demo_drive.hpp, hands them over; drive.hpp writes them).
//
// The demo vehicle (config/demo_vehicle.dbc, compiled into this library) is a front-engined
// car with a rear e-axle. Its messages, transmitted at their GenMsgCycleTime from sample k at
// t_k = k / 100 Hz, each at a fixed phase after t_k (bus serialisation, ~0.25 ms per frame):
//
//   message (id)               cycle  phase    signals (factor, unit)                 byte order
//   Chassis_Level (0x3D0)      20 ms  +0       Level_Page switch, alternating: page 1 =
//                                              Level_RearRight (0.01 mm, signed) and
//                                              Level_RearLeft (SNA), page 0 = front (SNA);
//                                              each page every 40 ms                   Intel
//   PT_WheelTorque (0x0A8)     10 ms  +0.2 ms  WheelTorque_Front/_Rear (0.5 N*m, signed),
//                                              Gear (signed 4 bit)                     Intel
//   ESP_Dynamics (0x130)       10 ms  +0.45 ms LongAccel, LatAccel (0.01 m/s^2), YawRate
//                                              (0.01 deg/s), all signed                Motorola
//   ESP_Speed (0x1A0)          10 ms  +0.7 ms  VehicleSpeed (0.01 km/h, unsigned)     Intel
//   ESP_Brake (0x1B0)          10 ms  +0.95 ms BrakePressure (0.05 bar, 12 bit)       Motorola
//   EPS_Steering (0x18FF1010,  10 ms  +1.2 ms  SteeringWheelAngle (0.1 deg, signed)   Motorola
//                 29-bit)
//   IC_Odometer (0x520, 4 B)   100 ms +51.45ms Odometer (0.001 km, 32 bit; not an input) Intel
//
// Every message but the odometer carries a 4-bit rolling counter. The first frame of a log is
// Chassis_Level at t_0 = 0, so ticks at t_0 + k * 10 ms (the replay's grid) see every 10 ms
// message of sample k - 1: all inputs one tick late, none misaligned. Every input the
// estimator's dynamics use is sent at 10 ms: sent at 20 ms instead, the gear, brake pressure or
// steering angle each moved the final error of paper_exp2 by up to 0.1 percentage point against
// samples.csv, the wheel torque by up to 0.6; the 40 ms level page moves it by less than 0.001.
//
// The factors are the SensorSpec resolutions, so the quantised samples survive the round trip
// (values in deg, km/h, bar and mm differ from the samples by rounding only). The wheel torque
// T (a multiple of 0.5 N*m) is split into rear = 0.5 round(0.25 T / 0.5) and front = T - rear,
// which sum back to T exactly. A message whose inputs are invalid in the sample is not sent. Log
// times are simulation times (the first frame at 0.000000), so truth.csv lines up with them.
//
// Pure functions; thread-safe.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "vmass/can/can_frame.hpp"
#include "vmass/sim/simulator.hpp"

namespace vmass::sim {

/// The demo vehicle's DBC (the text of config/demo_vehicle.dbc).
std::string_view demo_vehicle_dbc();

/// The config's `can:` section (top-level YAML, ends with a newline) mapping the demo DBC,
/// named `dbc_file` relative to the config, to every estimator input.
std::string demo_can_config_yaml(const std::string& dbc_file = "vehicle.dbc");

/// The frames of a simulated drive in time order. "" or a message.
std::string make_can_frames(const SimulationResult& result, std::vector<can::CanFrame>* frames);

}  // namespace vmass::sim

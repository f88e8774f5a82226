#include "vmass/core/sample.hpp"

#include "vmass/core/regression_pair.hpp"

namespace vmass {

std::string_view input_name(Input in) {
  switch (in) {
    case Input::kWheelTorque:
      return "wheel_torque";
    case Input::kBrakePressure:
      return "brake_pressure";
    case Input::kAccelX:
      return "accel_x";
    case Input::kAccelY:
      return "accel_y";
    case Input::kYawRate:
      return "yaw_rate";
    case Input::kSpeed:
      return "speed";
    case Input::kSteeringWheelAngle:
      return "steering_wheel_angle";
    case Input::kRearRightDeflection:
      return "rear_right_deflection";
    case Input::kGear:
      return "gear";
    case Input::kBrakeSwitch:
      return "brake_switch";
    case Input::kEngineTorque:
      return "engine_torque";
    case Input::kEngineSpeed:
      return "engine_speed";
    case Input::kCount:
      break;
  }
  return "unknown";
}

std::string_view block_name(Block b) {
  return b == Block::kLongitudinal ? "longitudinal" : "lateral";
}

double Sample::value(Input in) const {
  switch (in) {
    case Input::kWheelTorque:
      return wheel_torque_nm;
    case Input::kBrakePressure:
      return brake_pressure_pa;
    case Input::kAccelX:
      return accel_x_mps2;
    case Input::kAccelY:
      return accel_y_mps2;
    case Input::kYawRate:
      return yaw_rate_radps;
    case Input::kSpeed:
      return speed_mps;
    case Input::kSteeringWheelAngle:
      return steering_wheel_angle_rad;
    case Input::kRearRightDeflection:
      return rear_right_deflection_m;
    case Input::kGear:
      return static_cast<double>(gear);
    case Input::kBrakeSwitch:
      return brake_switch ? 1.0 : 0.0;
    case Input::kEngineTorque:
      return engine_torque_nm;
    case Input::kEngineSpeed:
      return engine_speed_radps;
    case Input::kCount:
      break;
  }
  return 0.0;
}

void Sample::set(Input in, double v) {
  switch (in) {
    case Input::kWheelTorque:
      wheel_torque_nm = v;
      break;
    case Input::kBrakePressure:
      brake_pressure_pa = v;
      break;
    case Input::kAccelX:
      accel_x_mps2 = v;
      break;
    case Input::kAccelY:
      accel_y_mps2 = v;
      break;
    case Input::kYawRate:
      yaw_rate_radps = v;
      break;
    case Input::kSpeed:
      speed_mps = v;
      break;
    case Input::kSteeringWheelAngle:
      steering_wheel_angle_rad = v;
      break;
    case Input::kRearRightDeflection:
      rear_right_deflection_m = v;
      break;
    case Input::kGear:
      gear = static_cast<int>(v);
      break;
    case Input::kBrakeSwitch:
      brake_switch = v > 0.5;
      break;
    case Input::kEngineTorque:
      engine_torque_nm = v;
      break;
    case Input::kEngineSpeed:
      engine_speed_radps = v;
      break;
    case Input::kCount:
      return;
  }
  valid |= input_bit(in);
}

}  // namespace vmass

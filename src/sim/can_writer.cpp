#include "vmass/sim/can_writer.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <optional>
#include <sstream>

#include "vmass/can/dbc.hpp"
#include "vmass/can/decoder.hpp"
#include "vmass/core/constants.hpp"

namespace vmass::sim {

namespace detail {
extern const char* const kDemoVehicleDbc;  // demo_vehicle_dbc.cpp, generated from the DBC file
}

namespace {

/// One message of the demo car: who sends it when.
struct Schedule {
  const char* name;
  int period_ticks;  ///< cycle time / 10 ms
  int phase_ticks;   ///< sent at ticks k with k % period == phase
  TimeUs offset_us;  ///< after t_k
};

const Schedule kSchedule[] = {
    {"Chassis_Level", 2, 0, 0},   {"PT_WheelTorque", 1, 0, 200}, {"ESP_Dynamics", 1, 0, 450},
    {"ESP_Speed", 1, 0, 700},     {"ESP_Brake", 1, 0, 950},      {"EPS_Steering", 1, 0, 1200},
    {"IC_Odometer", 10, 5, 1450},
};

// Signal values of one message for sample s; false when an input it carries is invalid.
class Encoder {
 public:
  explicit Encoder(can::Decoder decoder) : decoder_(std::move(decoder)) {}

  int message(const char* name) const { return decoder_.find_message(name); }
  int signal(int m, const char* name) const {
    return decoder_.database().messages[static_cast<std::size_t>(m)].find_signal(name);
  }

  bool fill(const std::string& name, const Sample& s, double distance_m, std::int64_t cycle_index,
            int m, double* v) const {
    auto set = [&](const char* signal_name, double value) {
      const int i = signal(m, signal_name);
      if (i >= 0) v[i] = value;
    };
    const double counter = static_cast<double>(cycle_index % 16);
    if (name == "Chassis_Level") {
      if (!s.has(Input::kRearRightDeflection)) return false;
      const bool rear = cycle_index % 2 == 0;
      set("Level_Page", rear ? 1.0 : 0.0);
      set("Level_Counter", counter);
      set("Level_FrontLeft", -327.68);  // SNA: the demo car measures the rear right only
      set("Level_FrontRight", -327.68);
      set("Level_RearLeft", -327.68);
      set("Level_RearRight", s.rear_right_deflection_m * 1e3);
      return true;
    }
    if (name == "PT_WheelTorque") {
      if (!s.has(Input::kWheelTorque) || !s.has(Input::kGear)) return false;
      const double total_half_nm = std::nearbyint(s.wheel_torque_nm / 0.5);
      const double rear_half_nm = std::nearbyint(0.25 * total_half_nm);
      set("WheelTorque_Front", 0.5 * (total_half_nm - rear_half_nm));
      set("WheelTorque_Rear", 0.5 * rear_half_nm);
      set("Gear", static_cast<double>(s.gear));
      set("PT_Counter", counter);
      return true;
    }
    if (name == "IC_Odometer") {
      set("Odometer", distance_m * 1e-3);
      return true;
    }
    if (name == "ESP_Dynamics") {
      if (!s.has(Input::kAccelX) || !s.has(Input::kAccelY) || !s.has(Input::kYawRate)) {
        return false;
      }
      set("LongAccel", s.accel_x_mps2);
      set("LatAccel", s.accel_y_mps2);
      set("YawRate", s.yaw_rate_radps * 180.0 / kPi);
      set("ESP_Dynamics_Counter", counter);
      return true;
    }
    if (name == "ESP_Speed") {
      if (!s.has(Input::kSpeed)) return false;
      set("VehicleSpeed", s.speed_mps * 3.6);
      set("ESP_Speed_Counter", counter);
      return true;
    }
    if (name == "ESP_Brake") {
      if (!s.has(Input::kBrakePressure)) return false;
      set("BrakePressure", s.brake_pressure_pa * 1e-5);
      set("ESP_Brake_Counter", counter);
      return true;
    }
    if (name == "EPS_Steering") {
      if (!s.has(Input::kSteeringWheelAngle)) return false;
      set("SteeringWheelAngle", s.steering_wheel_angle_rad * 180.0 / kPi);
      set("EPS_Counter", counter);
      return true;
    }
    return false;
  }

  const can::Decoder& decoder() const { return decoder_; }

 private:
  can::Decoder decoder_;
};

std::optional<can::Decoder> compile_demo_dbc(std::string* error) {
  can::DbcParseResult parsed = can::parse_dbc(demo_vehicle_dbc(), "demo_vehicle.dbc");
  if (!parsed.ok()) {
    for (const auto& d : parsed.diagnostics) {
      if (d.severity == can::Severity::kError) *error = d.to_string();
    }
    return std::nullopt;
  }
  return can::Decoder::compile(std::move(parsed.database), error);
}

}  // namespace

std::string_view demo_vehicle_dbc() { return detail::kDemoVehicleDbc; }

std::string demo_can_config_yaml(const std::string& dbc_file) {
  std::ostringstream os;
  os << "can:\n"
     << "  dbc: " << dbc_file << "                # the demo vehicle (config/demo_vehicle.dbc)\n"
     << "  inputs:                         # units come from the DBC (Nm, bar, m/s^2, deg/s, "
        "km/h, deg, mm)\n"
     << "    wheel_torque:                 # front engine + rear e-axle, both at the wheels\n"
     << "      sum:\n"
     << "        - {message: PT_WheelTorque, signal: WheelTorque_Front, gain: 1.0}\n"
     << "        - {message: PT_WheelTorque, signal: WheelTorque_Rear, gain: 1.0}\n"
     << "    brake_pressure: {message: ESP_Brake, signal: BrakePressure}\n"
     << "    accel_x: {message: ESP_Dynamics, signal: LongAccel}\n"
     << "    accel_y: {message: ESP_Dynamics, signal: LatAccel}\n"
     << "    yaw_rate: {message: ESP_Dynamics, signal: YawRate}\n"
     << "    speed: {message: ESP_Speed, signal: VehicleSpeed}\n"
     << "    steering_wheel_angle: {message: EPS_Steering, signal: SteeringWheelAngle}\n"
     << "    rear_right_deflection: {message: Chassis_Level, signal: Level_RearRight, mux: 1}\n"
     << "    gear: {message: PT_WheelTorque, signal: Gear}\n";
  return os.str();
}

std::string make_can_frames(const SimulationResult& result, std::vector<can::CanFrame>* frames) {
  std::string error;
  std::optional<can::Decoder> decoder = compile_demo_dbc(&error);
  if (!decoder) return "demo_vehicle.dbc: " + error;
  const Encoder encoder(std::move(*decoder));
  struct Slot {
    const Schedule* schedule;
    int message;
  };
  std::vector<Slot> slots;
  for (const Schedule& s : kSchedule) {
    const int m = encoder.message(s.name);
    if (m < 0) return std::string("demo_vehicle.dbc: no message ") + s.name;
    slots.push_back({&s, m});
  }
  std::vector<double> values(static_cast<std::size_t>(encoder.decoder().max_signals_per_message()));
  frames->clear();
  frames->reserve(result.samples.size() * 5);
  for (std::size_t k = 0; k < result.samples.size(); ++k) {
    const Sample& s = result.samples[k];
    const auto tick = static_cast<std::int64_t>(k);
    for (const Slot& slot : slots) {
      const Schedule& sch = *slot.schedule;
      if (tick % sch.period_ticks != sch.phase_ticks) continue;
      std::fill(values.begin(), values.end(), 0.0);
      const double distance_m = k < result.truth.size() ? result.truth[k].distance_m : 0.0;
      if (!encoder.fill(sch.name, s, distance_m, tick / sch.period_ticks, slot.message,
                        values.data())) {
        continue;
      }
      can::CanFrame f;
      encoder.decoder().encode(slot.message, values.data(), &f);
      f.time_us = s.time_us + sch.offset_us;
      frames->push_back(f);
    }
  }
  return "";
}

}  // namespace vmass::sim

#include "vmass/sim/realism.hpp"

#include <array>

namespace vmass::sim {

namespace {

struct EffectInfo {
  std::string_view name;
  std::string_view description;
};

constexpr std::array<EffectInfo, kEffectCount> kEffects = {{
    {"driveline_mode", "lightly damped torsional mode (2-10 Hz) between reported and hub torque"},
    {"driveline_lag", "the hub torque lags the ECU's report by 10-40 ms"},
    {"torque_converter", "automatic: torque multiplication up to ~2x when unlocked, ECU model off"},
    {"engine_drag", "overrun drag torque, reported with a 20-40 % error"},
    {"accessory_loads", "A/C compressor switching, left out of the reported torque"},
    {"creep", "automatic: creep torque at low speed"},
    {"regen_braking", "electric: negative wheel torque with no brake pressure"},
    {"abs_esc", "friction-limited braking (ABS) and ESC brake interventions"},
    {"imu_filter", "the accelerometer's own 20-40 Hz low-pass"},
    {"imu_bias_drift", "accelerometer bias and random-walk drift"},
    {"sensor_noise",
     "white noise on every sensor signal (accelerometers, gyro, speed, pressure, ...)"},
    {"imu_vibration", "8-25 Hz vibration growing with speed and roughness, engine orders"},
    {"imu_mounting", "IMU misalignment and lever arm away from the centre of gravity"},
    {"body_pitch_roll", "body pitch and roll per g tilt the accelerometer"},
    {"wind", "mean head and cross wind with gusts"},
    {"speed_resistance", "rolling resistance growing with v^2, driveline viscous losses"},
    {"wheel_speed",
     "speed from the wheels: slip (the driveline turns with it), radius error, quantisation, "
     "cluster display"},
    {"brake_sensor", "brake pressure sensor offset"},
    {"brake_fade", "brake gain falls with disc temperature"},
    {"road_roughness", "rough surface and speed bumps"},
    {"bus_timing", "each ECU's own cycle time, phase and filter latency"},
    {"mass_uncertainty", "true empty mass differs from the datasheet (fuel, options)"},
    {"payload_position", "payload in seats and boot, not at the centre of gravity"},
    {"datasheet_errors", "config values carry realistic errors (C_alpha, K_brake, m_rot, c)"},
}};

}  // namespace

std::string_view effect_name(Effect e) {
  const auto i = static_cast<std::size_t>(e);
  return i < kEffects.size() ? kEffects[i].name : "unknown";
}

std::string_view effect_description(Effect e) {
  const auto i = static_cast<std::size_t>(e);
  return i < kEffects.size() ? kEffects[i].description : "";
}

std::optional<Effect> parse_effect(std::string_view name) {
  for (std::size_t i = 0; i < kEffects.size(); ++i) {
    if (kEffects[i].name == name) return static_cast<Effect>(i);
  }
  return std::nullopt;
}

std::vector<Effect> all_effects() {
  std::vector<Effect> out;
  for (int i = 0; i < kEffectCount; ++i) out.push_back(static_cast<Effect>(i));
  return out;
}

std::string Realism::describe() const {
  if (*this == all()) return "all";
  if (!any()) return "none";
  std::string out;
  for (Effect e : all_effects()) {
    if (!has(e)) continue;
    if (!out.empty()) out += '+';
    out += effect_name(e);
  }
  return out;
}

std::optional<Realism> Realism::parse(std::string_view text) {
  if (text == "all") return all();
  if (text == "none") return none();
  if (text.substr(0, 4) == "all-") {
    const auto e = parse_effect(text.substr(4));
    if (!e) return std::nullopt;
    return all().without(*e);
  }
  Realism out = none();
  while (!text.empty()) {
    const std::size_t plus = text.find('+');
    const auto e = parse_effect(text.substr(0, plus));
    if (!e) return std::nullopt;
    out = out.with(*e);
    if (plus == std::string_view::npos) break;
    text.remove_prefix(plus + 1);
  }
  return out;
}

}  // namespace vmass::sim

#include "vmass/signals/plausibility_params.hpp"

#include "vmass/config/yaml_reader.hpp"

namespace vmass::signals {
namespace {

void read_limits(YamlReader& r, InputLimits* l) {
  r.read("min", &l->min);
  r.read("max", &l->max);
  r.read("max_rate_per_s", &l->max_rate_per_s);
  r.read("stuck_s", &l->stuck_s);
  r.read("stuck_band", &l->stuck_band);
  if (!(l->min < l->max)) r.fail("max", "must be above min");
  if (!(l->max_rate_per_s >= 0.0)) r.fail("max_rate_per_s", "must be >= 0 (0: off)");
  if (!(l->stuck_s >= 0.0)) r.fail("stuck_s", "must be >= 0 (0: off)");
  if (!(l->stuck_band >= 0.0)) r.fail("stuck_band", "must be >= 0 (0: bit for bit)");
  r.reject_unknown_keys();
}

void read_speed_accel(YamlReader r, SpeedAccelCheck* c) {
  r.read("enabled", &c->enabled);
  r.read("window_s", &c->window_s);
  r.read("tolerance_mps", &c->tolerance_mps);
  r.read("tolerance_fraction", &c->tolerance_fraction);
  r.read("smoothing_s", &c->smoothing_s);
  r.read("scale_tolerance", &c->scale_tolerance);
  r.read("scale_time_s", &c->scale_time_s);
  if (!(c->window_s >= 0.05 && c->window_s <= 10.0)) r.fail("window_s", "must be in [0.05, 10]");
  if (!(c->tolerance_mps > 0.0)) r.fail("tolerance_mps", "must be > 0");
  if (!(c->tolerance_fraction >= 0.0)) r.fail("tolerance_fraction", "must be >= 0");
  if (!(c->smoothing_s > c->window_s)) r.fail("smoothing_s", "must be above window_s");
  if (!(c->scale_tolerance >= 0.0)) r.fail("scale_tolerance", "must be >= 0 (0: off)");
  if (!(c->scale_time_s > c->smoothing_s)) r.fail("scale_time_s", "must be above smoothing_s");
  r.reject_unknown_keys();
}

void read_yaw_accel(YamlReader r, YawAccelCheck* c) {
  r.read("enabled", &c->enabled);
  r.read("window_s", &c->window_s);
  r.read("min_speed_mps", &c->min_speed_mps);
  r.read("min_accel_y_mps2", &c->min_accel_y_mps2);
  r.read("steady_accel_y_mps2", &c->steady_accel_y_mps2);
  r.read("steady_yaw_rate_radps", &c->steady_yaw_rate_radps);
  r.read("tolerance_radps", &c->tolerance_radps);
  r.read("tolerance_fraction", &c->tolerance_fraction);
  if (!(c->window_s >= 0.05 && c->window_s <= 10.0)) r.fail("window_s", "must be in [0.05, 10]");
  if (!(c->min_speed_mps > 0.0)) r.fail("min_speed_mps", "must be > 0");
  if (!(c->tolerance_radps > 0.0)) r.fail("tolerance_radps", "must be > 0");
  if (!(c->tolerance_fraction >= 0.0)) r.fail("tolerance_fraction", "must be >= 0");
  r.reject_unknown_keys();
}

}  // namespace

std::array<InputLimits, kInputCount> PlausibilityParams::default_input_limits() {
  std::array<InputLimits, kInputCount> l{};
  auto set = [&l](Input in, InputLimits v) { l[static_cast<std::size_t>(in)] = v; };
  set(Input::kWheelTorque, {-3e5, 3e5, 0.0, 0.0, 0.0});
  set(Input::kBrakePressure, {-2e5, 3e7, 0.0, 0.0, 0.0});
  set(Input::kAccelX, {-30.0, 30.0, 0.0, 0.0, 0.05});  // frozen: speed_vs_accel_x sees it
  set(Input::kAccelY, {-30.0, 30.0, 0.0, 5.0, 0.05});
  set(Input::kYawRate, {-5.0, 5.0, 30.0, 5.0, 0.01});
  set(Input::kSpeed, {-15.0, 120.0, 50.0, 0.0, 0.0});
  set(Input::kSteeringWheelAngle, {-20.0, 20.0, 40.0, 5.0, 0.035});
  set(Input::kRearRightDeflection, {-0.5, 0.5, 5.0, 0.0, 0.0});
  set(Input::kGear, {-5.0, 30.0, 0.0, 0.0, 0.0});
  set(Input::kBrakeSwitch, {0.0, 1.0, 0.0, 0.0, 0.0});
  set(Input::kEngineTorque, {-2e4, 2e4, 0.0, 0.0, 0.0});      // a heavy truck's engine: 3.5 kN m
  set(Input::kEngineSpeed, {-200.0, 2000.0, 0.0, 0.0, 0.0});  // rad/s: an e-motor's 19000 rpm
  return l;
}

std::string parse_plausibility(const YAML::Node& node, const std::string& file,
                               PlausibilityParams* out) {
  try {
    YamlReader r(node, file, "can.plausibility");
    PlausibilityParams p;
    r.read("enabled", &p.enabled);
    YamlReader inputs = r.child("inputs");
    for (int i = 0; i < kInputCount; ++i) {
      const std::string name(input_name(static_cast<Input>(i)));
      if (!inputs.has(name)) continue;
      YamlReader one = inputs.child(name);
      read_limits(one, &p.inputs[static_cast<std::size_t>(i)]);
    }
    inputs.reject_unknown_keys();
    read_speed_accel(r.child("speed_vs_accel_x"), &p.speed_vs_accel_x);
    read_yaw_accel(r.child("yaw_rate_vs_accel_y"), &p.yaw_rate_vs_accel_y);
    r.reject_unknown_keys();
    *out = p;
    return "";
  } catch (const ConfigError& e) {
    return e.what();
  } catch (const YAML::Exception& e) {
    return file + ":" + std::to_string(e.mark.line + 1) + ": can.plausibility: " + e.msg;
  }
}

}  // namespace vmass::signals

// Decodes a wheel-speed frame with vmass::can and hands it to the vmass::core estimator as one
// tick; loads a vehicle's config with vmass::config into an estimator, and says where a broken
// config is wrong: what a ROS 2 node or a team's own daemon does with the installed package.
//   outside CONFIG BROKEN_CONFIG
#include <cstdio>
#include <string>

#include <vmass/can/dbc.hpp>
#include <vmass/can/decoder.hpp>
#include <vmass/config/config.hpp>
#include <vmass/core/pipeline.hpp>

namespace {

// The estimator from a config file, as vmassd builds it; then the error of a broken one.
int load_configs(const char* path, const char* broken_path) {
  const vmass::ConfigLoad load = vmass::load_config(path);
  if (!load.ok()) {
    std::printf("config: %s\n", load.error.c_str());
    return 1;
  }
  const vmass::Pipeline pipeline(load.config->pipeline);
  std::printf("config: empty mass %.1f kg, estimator %s\n",
              load.config->pipeline.vehicle.empty_mass_kg,
              std::string(pipeline.regressor().name()).c_str());
  const vmass::ConfigLoad broken = vmass::load_config(broken_path);
  if (broken.ok()) {
    std::printf("broken: loaded without an error\n");
    return 1;
  }
  std::printf("broken: %s\n", broken.error.c_str());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 3) {
    std::printf("usage: outside CONFIG BROKEN_CONFIG\n");
    return 2;
  }
  const char* dbc =
      "VERSION \"\"\nBU_: ESP\nBO_ 256 ESP_Speed: 2 ESP\n"
      " SG_ VehicleSpeed : 0|16@1+ (0.01,0) [0|655.35] \"km/h\" Vector__XXX\n";
  vmass::can::DbcParseResult parsed = vmass::can::parse_dbc(dbc, "outside.dbc");
  std::string error;
  auto decoder = vmass::can::Decoder::compile(parsed.database, &error);
  if (!decoder) {
    std::printf("decoder: %s\n", error.c_str());
    return 1;
  }
  vmass::can::CanFrame frame;
  frame.id = 256;
  frame.len = 2;
  frame.data[0] = 0x10;  // 10000 * 0.01 = 100 km/h
  frame.data[1] = 0x27;
  double speed_kmh = -1.0;
  decoder->decode(frame, [&](int, double v) { speed_kmh = v; });

  vmass::PipelineParams params;
  params.vehicle.empty_mass_kg = 1500.0;
  params.vehicle.wheelbase_m = 2.7;
  params.vehicle.cg_to_front_axle_m = 1.2;
  params.vehicle.wheel_radius_m = 0.31;
  params.vehicle.brake_gain_n_per_pa = 0.0033;
  params.vehicle.steering_ratio = 15.5;
  params.vehicle.cornering_stiffness_front_n_per_rad = 150000.0;
  params.vehicle.cornering_stiffness_rear_n_per_rad = 170000.0;
  params.suspension.stiffness_n_per_m = 30000.0;
  if (const std::string invalid = params.validate(); !invalid.empty()) {
    std::printf("params: %s\n", invalid.c_str());
    return 1;
  }
  vmass::Pipeline pipeline(params);
  vmass::Sample sample;
  sample.time_us = 0;
  sample.speed_mps = speed_kmh / 3.6;
  sample.valid = vmass::input_bit(vmass::Input::kSpeed);
  pipeline.step(sample);
  std::printf("speed %.1f km/h, estimator %s\n", speed_kmh,
              std::string(pipeline.regressor().name()).c_str());
  return load_configs(argv[1], argv[2]);
}

// Given the simulator's paper_exp2 drive, when the demo vehicle's frames (vmass-sim's drive.log)
// go through the config's mapping into a SignalTable ticked at t0 + k * 10 ms, then every tick's
// Sample equals the simulated sample one tick earlier (the frames leave 0.2-1.2 ms after their
// sample; the level page at the sample's time) to within rounding, for every input; the log text
// reads back to the same frames; and the DBC compiled into the simulator is
// config/demo_vehicle.dbc. (Compiled only when the simulator is part of the build.)
#include <gtest/gtest.h>
#include <bitset>

#include <bitset>
#include <cmath>
#include <fstream>
#include <sstream>

#include "vmass/can/candump.hpp"
#include "vmass/can/dbc.hpp"
#include "vmass/signals/signal_table.hpp"
#include "vmass/sim/can_writer.hpp"
#include "vmass/sim/scenario.hpp"
#include "vmass/sim/sensor_model.hpp"
#include "vmass/sim/simulator.hpp"

namespace vmass::signals {
namespace {

std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(SimCan, DemoDbcIsTheCheckedInFile) {
  EXPECT_EQ(std::string(sim::demo_vehicle_dbc()),
            read_file(std::string(VMASS_SOURCE_DIR) + "/config/demo_vehicle.dbc"));
  const can::DbcParseResult r =
      can::parse_dbc(sim::demo_vehicle_dbc(), "demo_vehicle.dbc", can::DbcParseOptions{true});
  EXPECT_TRUE(r.ok());
  EXPECT_EQ(r.warning_count(), 0);  // clean even in strict mode
}

TEST(SimCan, FramesDecodeBackToTheSimulatedSamples) {
  const auto scenario = sim::find_scenario("paper_exp2");
  ASSERT_TRUE(scenario.has_value());
  sim::SimulationResult result;
  ASSERT_EQ(sim::simulate(*scenario, {}, &result), "");
  std::vector<can::CanFrame> frames;
  ASSERT_EQ(sim::make_can_frames(result, &frames), "");
  ASSERT_GT(frames.size(), result.samples.size() * 5);

  // The candump text reads back to the same frames.
  std::stringstream log;
  can::CandumpWriter writer(log);
  for (const can::CanFrame& f : frames) writer.write(f, "can0");
  can::CandumpReader reader(log, "drive.log");
  can::CandumpRecord rec;
  std::size_t n = 0;
  while (reader.next(&rec)) {
    ASSERT_LT(n, frames.size());
    const can::CanFrame& f = frames[n++];
    ASSERT_EQ(rec.frame.time_us, f.time_us);
    ASSERT_EQ(rec.frame.id, f.id);
    ASSERT_EQ(rec.frame.flags, f.flags);
    ASSERT_EQ(rec.frame.len, f.len);
    ASSERT_EQ(std::memcmp(rec.frame.data, f.data, f.len), 0);
  }
  EXPECT_EQ(n, frames.size());
  EXPECT_EQ(reader.stats().corrupt, 0u);

  // The config's mapping, as vmass-sim writes it.
  can::DbcParseResult parsed = can::parse_dbc(sim::demo_vehicle_dbc(), "vehicle.dbc");
  auto decoder = std::make_shared<const can::Decoder>(
      std::move(*can::Decoder::compile(std::move(parsed.database))));
  const YAML::Node can = YAML::Load(sim::demo_can_config_yaml())["can"];
  EXPECT_EQ(can["dbc"].as<std::string>(), "vehicle.dbc");
  SignalMapping mapping;
  ASSERT_EQ(parse_signal_mapping(can["inputs"], "config.yaml", *decoder, "vehicle.dbc", &mapping),
            "");
  // The demo car's bus carries what the sensor model measures (wheel torque, brake pressure).
  EXPECT_EQ(mapping.inputs.size(),
            static_cast<std::size_t>(std::bitset<32>(sim::kSensorModelInputs).count()));
  SignalTable table(decoder, mapping);

  const TimeUs t0 = frames.front().time_us;
  std::size_t next = 0;
  int compared = 0;
  for (std::size_t k = 0; k < result.samples.size(); ++k) {
    const TimeUs tick = t0 + static_cast<TimeUs>(k) * 10000;
    while (next < frames.size() && frames[next].time_us <= tick) {
      table.on_frame(frames[next], frames[next].time_us);
      ++next;
    }
    const Sample s = table.sample_at(tick);
    if (k == 0) continue;
    ASSERT_EQ(s.valid, sim::kSensorModelInputs) << "tick " << k;
    const Sample& want = result.samples[k - 1];
    ASSERT_EQ(s.wheel_torque_nm, want.wheel_torque_nm) << k;  // 0.5 N*m steps: exact
    ASSERT_EQ(s.gear, want.gear) << k;
    ASSERT_NEAR(s.brake_pressure_pa, want.brake_pressure_pa, 1e-6) << k;
    ASSERT_NEAR(s.accel_x_mps2, want.accel_x_mps2, 1e-12) << k;
    ASSERT_NEAR(s.accel_y_mps2, want.accel_y_mps2, 1e-12) << k;
    ASSERT_NEAR(s.yaw_rate_radps, want.yaw_rate_radps, 1e-12) << k;
    ASSERT_NEAR(s.speed_mps, want.speed_mps, 1e-12) << k;
    ASSERT_NEAR(s.steering_wheel_angle_rad, want.steering_wheel_angle_rad, 1e-12) << k;
    // The rear level page leaves every 40 ms, with sample 4j, at t_4j itself.
    const std::size_t page = k / 4 * 4;
    ASSERT_NEAR(s.rear_right_deflection_m, result.samples[page].rear_right_deflection_m, 1e-12)
        << k;
    ++compared;
  }
  EXPECT_EQ(compared, static_cast<int>(result.samples.size()) - 1);
  for (; next < frames.size(); ++next) table.on_frame(frames[next], frames[next].time_us);
  const SignalTableCounters& c = table.counters();
  EXPECT_EQ(c.decoded, frames.size());
  for (const InputCounters& ic : c.inputs) {
    EXPECT_EQ(ic.stale, 0u);
    EXPECT_EQ(ic.invalid_values, 0u);
  }
}

}  // namespace
}  // namespace vmass::signals

// A population vehicle's bus round trip through the product's path: its own DBC and the
// engineer's mapping, loaded by the real loaders, decoded by CandumpReader + the runtime's tick
// driver, give back the ECU signals within each signal's quantisation, whatever the vehicle's byte
// order, units and sign conventions.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "vmass/can/candump.hpp"
#include "vmass/config/config.hpp"
#include "vmass/runtime/can_input_source.hpp"
#include "vmass/runtime/candump_frame_source.hpp"
#include "vmass/runtime/tick_driver.hpp"
#include "vmass/signals/signal_mapping.hpp"
#include "vmass/signals/signal_table.hpp"
#include "vmass/sim/datasheet_config.hpp"
#include "vmass/sim/population.hpp"
#include "vmass/sim/population_drive.hpp"
#include "vmass/sim/population_scenarios.hpp"
#include "vmass/sim/vehicle_bus.hpp"

namespace vmass::sim {
namespace {

namespace fs = std::filesystem;

// Vehicles whose conventions differ: byte orders, g or m/s^2, yaw sign and unit, muxed level.
std::vector<DrawnVehicle> varied_vehicles() {
  std::vector<DrawnVehicle> out;
  bool motorola = false, intel = false, g = false, yaw_right = false, muxed = false;
  for (std::uint64_t seed = 1; seed < 400 && out.size() < 6; ++seed) {
    const DrawnVehicle d = draw_vehicle(static_cast<VehicleClass>(seed % 6), seed);
    const VehicleSensors& s = d.sensors;
    if (!s.deflection || !s.brake_pressure || !s.lateral || d.vehicle.rear_levelling ||
        s.torque == TorqueSignal::kEngineTorque || s.speed != SpeedSignal::kEsc) {
      continue;
    }
    const CanConventions& c = d.can;
    const bool news = (c.motorola && !motorola) || (!c.motorola && !intel) ||
                      (c.accel_in_g && !g) || (c.yaw_positive_right && !yaw_right) ||
                      (c.deflection_muxed && !muxed);
    if (!news) continue;
    motorola |= c.motorola;
    intel |= !c.motorola;
    g |= c.accel_in_g;
    yaw_right |= c.yaw_positive_right;
    muxed |= c.deflection_muxed;
    out.push_back(d);
  }
  return out;
}

TEST(VehicleBus, RoundTripThroughTheProductsLoadersGivesTheEcuSignals) {
  const std::vector<DrawnVehicle> vehicles = varied_vehicles();
  ASSERT_GE(vehicles.size(), 4u);
  const fs::path dir = fs::temp_directory_path() / "vmass_vehicle_bus_test";
  fs::create_directories(dir);
  for (const DrawnVehicle& d : vehicles) {
    PopulationRun run;
    ASSERT_EQ(make_population_run(d, "paper_exp2_eps1", 1, Realism::none(), &run), "");
    run.bus.eps = NoiseSet::kNone;
    DriveOutput drive;
    ASSERT_EQ(record_drive(population_drive(d, run, Knowledge::kKnownScale), &drive), "");
    ASSERT_EQ(write_drive_files(drive, dir.string()), "");
    const SimulationResult& result = drive.result;
    const ConfigLoad config = load_config((dir / "config.yaml").string());
    ASSERT_TRUE(config.ok()) << d.id << ": " << config.error;
    const signals::CanInputsLoad can = signals::load_can_inputs(*config.config);
    ASSERT_TRUE(can.ok()) << d.id << ": " << can.error;
    std::string error;
    auto log = runtime::CandumpFrameSource::open((dir / "drive.log").string(), &error);
    ASSERT_TRUE(log) << error;
    runtime::CanInputSource source(std::move(log), can.inputs->decoder, can.inputs->mapping);
    std::vector<Sample> samples;
    runtime::UnpacedClock clock;
    runtime::TickDriver(source, 100.0).run(clock, [&](std::int64_t, TimeUs t) {
      samples.push_back(source.sample_at(t));
    });
    ASSERT_GT(samples.size(), 10000u) << d.id;
    // Tick k sees the samples the ECUs took at k - 1 (or k): compare with the closer one.
    auto trace_at_tick = [&](std::size_t k) { return result.ecu_trace[k * 10]; };
    int compared = 0;
    for (std::size_t k = 2; k + 1 < samples.size(); ++k) {
      const Sample& s = samples[k];
      if (!s.has(Input::kYawRate) || !s.has(Input::kAccelX) || !s.has(Input::kSpeed)) continue;
      const EcuSignals& a = trace_at_tick(k - 1);
      const EcuSignals& b = trace_at_tick(k);
      auto near = [](double v, double x, double y, double tol) {
        return std::min(std::abs(v - x), std::abs(v - y)) <= tol;
      };
      EXPECT_TRUE(near(s.accel_x_mps2, a.accel_x_mps2, b.accel_x_mps2, 0.006)) << d.id << " " << k;
      EXPECT_TRUE(near(s.accel_y_mps2, a.accel_y_mps2, b.accel_y_mps2, 0.006)) << d.id << " " << k;
      EXPECT_TRUE(near(s.yaw_rate_radps, a.yaw_rate_radps, b.yaw_rate_radps, 1e-4)) << d.id;
      EXPECT_TRUE(near(s.speed_mps, a.speed_mps, b.speed_mps, 0.003)) << d.id << " " << k;
      EXPECT_TRUE(near(s.steering_wheel_angle_rad, a.steering_wheel_angle_rad,
                       b.steering_wheel_angle_rad, 0.0009))  // 0.1 deg steps
          << d.id << " " << s.steering_wheel_angle_rad << " " << a.steering_wheel_angle_rad;
      EXPECT_TRUE(near(s.wheel_torque_nm, a.wheel_torque_nm, b.wheel_torque_nm, 1.01)) << d.id;
      EXPECT_TRUE(near(s.brake_pressure_pa, a.brake_pressure_pa, b.brake_pressure_pa, 600.0))
          << d.id;
      ++compared;
    }
    EXPECT_GT(compared, 15000) << d.id;
  }
  fs::remove_all(dir);
}

}  // namespace
}  // namespace vmass::sim

// The population's torque-signal variants (vmass-suite --torque-signal): what each puts on a
// combustion vehicle's bus and in its config, through the product's loaders.
#include "vmass/sim/torque_signal_variant.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "vmass/config/config.hpp"
#include "vmass/signals/signal_mapping.hpp"
#include "vmass/sim/datasheet_config.hpp"
#include "vmass/sim/powertrain.hpp"
#include "vmass/sim/vehicle_bus.hpp"

namespace vmass::sim {
namespace {

namespace fs = std::filesystem;

struct Loaded {
  Config config;
  signals::SignalMapping mapping;
};

// The vehicle's DBC and the config its engineer writes, loaded as vmass-replay loads them.
Loaded load(const DrawnVehicle& d, Knowledge knowledge) {
  const fs::path dir = fs::temp_directory_path() / ("vmass_torque_variant_" + d.id);
  fs::create_directories(dir);
  const VehicleBus bus(d);
  EXPECT_EQ(bus.error(), "");
  std::ofstream(dir / "vehicle.dbc") << bus.dbc_text();
  std::ofstream(dir / "config.yaml")
      << datasheet_config_yaml(d, Realism::all(), knowledge, "vehicle.dbc");
  const ConfigLoad config = load_config((dir / "config.yaml").string());
  EXPECT_TRUE(config.ok()) << d.id << ": " << config.error;
  Loaded out;
  if (!config.ok()) return out;
  out.config = *config.config;
  const signals::CanInputsLoad can = signals::load_can_inputs(out.config);
  EXPECT_TRUE(can.ok()) << d.id << ": " << can.error;
  if (can.ok()) out.mapping = can.inputs->mapping;
  fs::remove_all(dir);
  return out;
}

TEST(TorqueSignalVariant, NamesRoundTrip) {
  for (auto v : {TorqueSignalVariant::kAsDrawn, TorqueSignalVariant::kEngineGearIndex,
                 TorqueSignalVariant::kEngineSpeedRatio}) {
    EXPECT_EQ(parse_torque_signal_variant(torque_signal_variant_name(v)), v);
  }
  EXPECT_FALSE(parse_torque_signal_variant("engine").has_value());
  EXPECT_EQ(torque_signal_variant_names(), "as_drawn, engine_gear_index, engine_speed_ratio");
}

TEST(TorqueSignalVariant, AsDrawnChangesNothing) {
  for (DrawnVehicle d : draw_population(14, kDevelopmentFirstSeed)) {
    const VehicleSensors before = d.sensors;
    apply_torque_signal_variant(TorqueSignalVariant::kAsDrawn, &d);
    EXPECT_EQ(d.sensors.torque, before.torque) << d.id;
    EXPECT_TRUE(d.sensors.gear_index) << d.id;
  }
}

TEST(TorqueSignalVariant, TheSpeedRatioConfigHasNoRatiosAndMapsNoGear) {
  int combustion = 0;
  for (DrawnVehicle d : draw_population(14, kDevelopmentFirstSeed)) {
    const TorqueSignal drawn = d.sensors.torque;
    apply_torque_signal_variant(TorqueSignalVariant::kEngineSpeedRatio, &d);
    const Loaded l = load(d, Knowledge::kDatasheetScale);
    const VehicleParams& v = l.config.pipeline.vehicle;
    if (d.electric) {
      EXPECT_EQ(d.sensors.torque, drawn) << d.id;
      EXPECT_FALSE(v.derive_overall_ratio) << d.id;
      continue;
    }
    ++combustion;
    EXPECT_TRUE(v.derive_overall_ratio) << d.id;
    EXPECT_FALSE(v.knows_driveline()) << d.id;
    EXPECT_TRUE(v.rotating_mass_by_gear_kg.empty()) << d.id;
    EXPECT_GT(v.engine_inertia_kgm2, 0.0) << d.id;
    EXPECT_EQ(v.torque_converter, d.vehicle.powertrain.has_torque_converter()) << d.id;
    EXPECT_DOUBLE_EQ(v.driveline_efficiency_accuracy_fraction, d.errors.declared_torque_accuracy)
        << d.id;
    EXPECT_NE(l.mapping.find(Input::kEngineTorque), nullptr) << d.id;
    EXPECT_NE(l.mapping.find(Input::kEngineSpeed), nullptr) << d.id;
    EXPECT_EQ(l.mapping.find(Input::kGear), nullptr) << d.id;
    EXPECT_EQ(l.mapping.find(Input::kWheelTorque), nullptr) << d.id;
  }
  EXPECT_GT(combustion, 5);
}

TEST(TorqueSignalVariant, TheGearIndexConfigHasTheRatiosAndMapsTheGear) {
  for (DrawnVehicle d : draw_population(14, kDevelopmentFirstSeed)) {
    if (d.electric) continue;
    apply_torque_signal_variant(TorqueSignalVariant::kEngineGearIndex, &d);
    const Loaded l = load(d, Knowledge::kKnownScale);
    const VehicleParams& v = l.config.pipeline.vehicle;
    EXPECT_FALSE(v.derive_overall_ratio) << d.id;
    const std::vector<double>& ratios = d.vehicle.powertrain.gear_ratios;
    ASSERT_EQ(v.gear_ratios.size(), ratios.size()) << d.id;
    for (std::size_t g = 0; g < ratios.size(); ++g) {
      EXPECT_NEAR(v.gear_ratios[g], ratios[g], 1e-6 * ratios[g]) << d.id;  // 9 digits in YAML
    }
    EXPECT_NE(l.mapping.find(Input::kGear), nullptr) << d.id;
    EXPECT_NE(l.mapping.find(Input::kEngineTorque), nullptr) << d.id;
  }
}

}  // namespace
}  // namespace vmass::sim

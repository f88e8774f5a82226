// The vehicle population: deterministic draws inside their class ranges, valid vehicles, the
// definition's hash, payload corner loads that balance, population scenarios that validate, and
// a datasheet config that never leaks the loaded state.
#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <string>

#include "sim_test_util.hpp"
#include "vmass/sim/datasheet_config.hpp"
#include "vmass/sim/population.hpp"
#include "vmass/sim/population_scenarios.hpp"
#include "vmass/sim/random_stream.hpp"
#include "vmass/sim/vehicle_bus.hpp"
#include "vmass/sim/vehicle_class.hpp"

#ifdef VMASS_SIM_HAVE_CONFIG_LOADER
#include "vmass/config/config.hpp"
#endif

namespace vmass::sim {
namespace {

constexpr double kG = 9.80665;

bool in(const Range& r, double v, double scale = 1.0) {
  return v >= r.low * scale - 1e-9 && v <= r.high * scale + 1e-9;
}

TEST(SimPopulation, DrawsAreDeterministicAndSeedsDiffer) {
  const DrawnVehicle a = draw_vehicle(VehicleClass::kSuv, 7);
  const DrawnVehicle b = draw_vehicle(VehicleClass::kSuv, 7);
  const DrawnVehicle c = draw_vehicle(VehicleClass::kSuv, 8);
  EXPECT_EQ(describe_vehicle(a), describe_vehicle(b));
  EXPECT_EQ(a.vehicle.empty.mass_kg, b.vehicle.empty.mass_kg);
  EXPECT_EQ(a.vehicle.imu.vibration_frequency_hz, b.vehicle.imu.vibration_frequency_hz);
  EXPECT_EQ(a.can.id_base, b.can.id_base);
  EXPECT_NE(a.vehicle.empty.mass_kg, c.vehicle.empty.mass_kg);
  DrawnVehicle parsed;
  std::string error;
  ASSERT_TRUE(parse_vehicle_id("suv-7", &parsed, &error)) << error;
  EXPECT_EQ(describe_vehicle(parsed), describe_vehicle(a));
  EXPECT_FALSE(parse_vehicle_id("bus-7", &parsed, &error));
  EXPECT_NE(error.find("unknown class 'bus'"), std::string::npos);
  EXPECT_FALSE(parse_vehicle_id("suv-x", &parsed, &error));
  EXPECT_FALSE(parse_vehicle_id("suv", &parsed, &error));
}

TEST(SimPopulation, EveryDrawIsValidAndInsideItsClassRanges) {
  for (const DrawnVehicle& d : draw_population(7 * 15, 1)) {
    const ClassDefinition& c = class_definition(d.vehicle_class);
    const TrueVehicle& v = d.vehicle;
    EXPECT_EQ(v.validate(), "") << d.id;
    EXPECT_EQ(d.true_vehicle(Realism::all()).validate(), "") << d.id;
    const double electric = d.electric ? 1.0 + c.electric_extra_mass_fraction.high : 1.0;
    EXPECT_TRUE(v.empty.mass_kg >= c.empty_mass_kg.low - 1e-9 &&
                v.empty.mass_kg <= c.empty_mass_kg.high * electric + 1e-9)
        << d.id;
    EXPECT_TRUE(in(c.wheelbase_m, v.wheelbase_m)) << d.id;
    EXPECT_TRUE(in(c.payload_capacity_kg, d.payload_capacity_kg)) << d.id;
    EXPECT_TRUE(in(c.cg_height_m, v.empty.cg_z_m)) << d.id;
    EXPECT_TRUE(in(c.mode_first_gear_hz, v.driveline.mode_frequency_first_gear_hz)) << d.id;
    EXPECT_NEAR(d.max_mass_kg, v.empty.mass_kg + d.payload_capacity_kg, 1e-9);
    EXPECT_FALSE(d.electric && d.sensors.torque == TorqueSignal::kEngineTorque) << d.id;
  }
}

TEST(SimPopulation, ClassesCycleAndHeldOutSeedsAreApart) {
  const auto dev = draw_population(14, kDevelopmentFirstSeed);
  const auto held = draw_population(14, kHeldOutFirstSeed);
  std::set<std::string> ids;
  for (int i = 0; i < 14; ++i) {
    EXPECT_EQ(dev[static_cast<std::size_t>(i)].vehicle_class, static_cast<VehicleClass>(i % 7));
    ids.insert(dev[static_cast<std::size_t>(i)].id);
    ids.insert(held[static_cast<std::size_t>(i)].id);
  }
  EXPECT_EQ(ids.size(), 28u);
}

TEST(SimPopulation, DefinitionHashCoversTheRangesAndTheRules) {
  const std::string text = population_definition_text();
  EXPECT_NE(text.find("heavy_truck.payload_capacity_kg = [13500, 17000] [TA] 26 t GVW"),
            std::string::npos);
  EXPECT_NE(text.find("rules v1"), std::string::npos);
  const std::string hash = population_definition_hash();
  EXPECT_EQ(hash.size(), 16u);
  char expected[17];
  std::snprintf(expected, sizeof expected, "%016llx",
                static_cast<unsigned long long>(hash_name(text.c_str())));
  EXPECT_EQ(hash, expected);
  for (const ClassDefinition& c : vehicle_classes()) {
    EXPECT_NE(std::string(c.empty_mass_kg.source), "") << vehicle_class_name(c.id);
  }
}

TEST(SimPopulation, PayloadCornerLoadsSumToTheWeightWithBalancedMoments) {
  TrueVehicle v;  // l = 2.70 m, track 1.55 m
  const LoadItem boot{100.0, 3.2, 0.3, 0.7};
  const MassProperties loaded = add_payload(v.empty, {boot});
  const StaticLoads s = static_loads(v, loaded);
  const double weight = loaded.mass_kg * kG;
  EXPECT_NEAR(s.front_left_n + s.front_right_n + s.rear_left_n + s.rear_right_n, weight, 1e-6);
  // Pitch: rear axle load x l = weight x x_cg (moments about the front axle).
  EXPECT_NEAR(s.rear_axle_n * v.wheelbase_m, weight * loaded.cg_x_m, 1e-6);
  // Roll: (left - right) x track / 2 = weight x y_cg.
  const double left = s.front_left_n + s.rear_left_n;
  const double right = s.front_right_n + s.rear_right_n;
  EXPECT_NEAR((left - right) * v.track_m / 2.0, weight * loaded.cg_y_m, 1e-6);
  // The boot load, behind the rear axle, takes load off the front axle: eq. (3), which puts it at
  // the CG, over-reads it from the rear corner.
  const StaticLoads empty = static_loads(v, v.empty);
  EXPECT_LT(s.front_axle_n, empty.front_axle_n);
  const double rear_added_n = s.rear_axle_n - empty.rear_axle_n;
  const double eq3_kg = 2.0 * (rear_added_n / 2.0) * v.wheelbase_m / (v.empty.cg_x_m * kG);
  EXPECT_GT(eq3_kg / 100.0, 2.0);
}

TEST(SimPopulation, EveryScenarioBuildsAValidRunForEveryClass) {
  for (int c = 0; c < kVehicleClassCount; ++c) {
    const DrawnVehicle d = draw_vehicle(static_cast<VehicleClass>(c), 3);
    for (const std::string& name : population_scenario_names()) {
      EXPECT_FALSE(population_scenario_description(name).empty());
      PopulationRun run;
      EXPECT_EQ(make_population_run(d, name, 1, Realism::all(), &run), "") << d.id << " " << name;
      EXPECT_GE(run.physics.duration_s, 150.0);
      EXPECT_LE(run.physics.mass_at(0.0).mass_kg, d.max_mass_kg * 1.05) << d.id << " " << name;
    }
  }
  PopulationRun run;
  EXPECT_NE(
      make_population_run(draw_vehicle(VehicleClass::kCompact, 1), "nope", 1, Realism::all(), &run),
      "");
}

TEST(SimPopulation, WithoutPayloadPositionEveryItemSitsAtTheEmptyCentreOfGravity) {
  const DrawnVehicle d = draw_vehicle(VehicleClass::kSaloon, 4);
  PopulationRun run;
  ASSERT_EQ(make_population_run(d, "heavy_rear_load", 1,
                                Realism::all().without(Effect::kPayloadPosition), &run),
            "");
  for (const LoadItem& it : run.physics.initial_payload) {
    EXPECT_DOUBLE_EQ(it.x_m, d.vehicle.empty.cg_x_m);
    EXPECT_DOUBLE_EQ(it.y_m, 0.0);
  }
  ASSERT_EQ(make_population_run(d, "heavy_rear_load", 1, Realism::all(), &run), "");
  EXPECT_GT(run.physics.mass_at(0.0).cg_x_m, d.vehicle.empty.cg_x_m);  // the load is behind
}

// The config the engineer writes: the empty car's CG and cornering stiffness, never the loaded
// state; exact without datasheet errors; the datasheet scale's radius and declared accuracies.
TEST(SimPopulation, DatasheetConfigNeverLeaksTheLoadedState) {
  DrawnVehicle d;
  for (std::uint64_t seed = 1; seed < 200; ++seed) {
    d = draw_vehicle(VehicleClass::kSuv, seed);
    if (d.sensors.deflection && !d.vehicle.rear_levelling &&
        d.sensors.torque != TorqueSignal::kEngineTorque && d.sensors.brake_pressure) {
      break;
    }
  }
  const std::string exact =
      datasheet_config_yaml(d, Realism::none(), Knowledge::kKnownScale, "vehicle.dbc");
  const std::string known =
      datasheet_config_yaml(d, Realism::all(), Knowledge::kKnownScale, "x.dbc");
  const std::string sheet =
      datasheet_config_yaml(d, Realism::all(), Knowledge::kDatasheetScale, "x.dbc");
  EXPECT_EQ(exact.find("estimator:"), std::string::npos);
  // Known scale: the torque and the radius are right, and the config says so.
  EXPECT_NE(known.find("wheel_torque_accuracy_fraction: 0\n"), std::string::npos);
  EXPECT_NE(known.find("wheel_radius_accuracy_fraction: 0\n"), std::string::npos);
  EXPECT_DOUBLE_EQ(torque_report_scale(d, Knowledge::kKnownScale), 1.0);
  EXPECT_DOUBLE_EQ(torque_report_scale(d, Knowledge::kDatasheetScale), 1.0 + d.errors.torque_scale);
#ifdef VMASS_SIM_HAVE_CONFIG_LOADER
  const ConfigLoad e = load_config_text(exact, "exact.yaml");
  ASSERT_TRUE(e.ok()) << e.error;
  const VehicleParams& v = e.config->pipeline.vehicle;
  EXPECT_NEAR(v.empty_mass_kg, d.vehicle.empty.mass_kg, 1e-3);
  EXPECT_NEAR(v.cg_to_front_axle_m, d.vehicle.empty.cg_x_m, 1e-6);
  const AxleCorneringStiffness cs = static_cornering_stiffness(d.vehicle, d.vehicle.empty);
  EXPECT_NEAR(v.cornering_stiffness_front_n_per_rad, cs.front_n_per_rad, 1e-3);
  EXPECT_NEAR(v.wheel_radius_m, d.vehicle.wheel_radius_m, 1e-9);
  EXPECT_NEAR(v.max_mass_kg, d.max_mass_kg, 1e-3);
  const ConfigLoad s = load_config_text(sheet, "sheet.yaml");
  ASSERT_TRUE(s.ok()) << s.error;
  const VehicleParams& vs = s.config->pipeline.vehicle;
  EXPECT_NEAR(vs.wheel_radius_m, d.vehicle.wheel_radius_m * (1.0 + d.errors.wheel_radius), 1e-6);
  // Datasheet scale: the declared accuracies (written, or the loader's equal defaults).
  EXPECT_EQ(vs.wheel_torque_accuracy_fraction, d.errors.declared_torque_accuracy);
  EXPECT_EQ(vs.wheel_radius_accuracy_fraction, d.errors.declared_radius_accuracy);
  EXPECT_NEAR(vs.brake_gain_n_per_pa, d.vehicle.brake_gain_n_per_pa * (1.0 + d.errors.brake_gain),
              1e-9);
  EXPECT_LE(std::abs(vs.cornering_stiffness_front_n_per_rad / cs.front_n_per_rad - 1.0),
            0.2 + 1e-6);
  EXPECT_NEAR(
      s.config->pipeline.suspension.stiffness_n_per_m,
      d.vehicle.rear_right_suspension.stiffness_n_per_m * (1.0 + d.errors.suspension_stiffness),
      1e-3);
#endif
}

TEST(SimPopulation, EveryVehicleBusCompilesItsDbc) {
  for (const DrawnVehicle& d : draw_population(70, 1)) {
    const VehicleBus bus(d);
    EXPECT_EQ(bus.error(), "") << d.id;
    EXPECT_NE(bus.can_config_yaml("v.dbc").find("accel_x:"), std::string::npos) << d.id;
  }
}

}  // namespace
}  // namespace vmass::sim

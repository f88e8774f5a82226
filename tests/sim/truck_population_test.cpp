// The truck population (issue 29): tractors apart from the car population, and its drives doing
// what they say: the torque at its limit, one gear and no brakes, a trailer coupled at a stop.
#include <gtest/gtest.h>

#include <algorithm>
#include <set>
#include <string>

#include "sim_test_util.hpp"
#include "vmass/sim/datasheet_config.hpp"
#include "vmass/sim/population.hpp"
#include "vmass/sim/population_scenarios.hpp"
#include "vmass/sim/truck_population.hpp"
#include "vmass/sim/vehicle_bus.hpp"

namespace vmass::sim {
namespace {

SimulationResult simulate_run(const DrawnVehicle& d, const std::string& scenario,
                              PopulationRun* run) {
  EXPECT_EQ(make_population_run(d, scenario, 1, Realism::all(), run), "") << d.id << scenario;
  SimulationOptions o = run->simulation;
  return test::run(run->physics, o);
}

TEST(SimTruckPopulation, TractorsAreHeavyTrucksWithACombinationLimitAndParseBack) {
  const std::vector<DrawnVehicle> trucks = draw_truck_population(3, kTruckFirstSeed);
  ASSERT_EQ(trucks.size(), 3U);
  for (const DrawnVehicle& t : trucks) {
    const DrawnVehicle rigid = draw_vehicle(VehicleClass::kHeavyTruck, t.seed);
    EXPECT_EQ(t.vehicle_class, VehicleClass::kHeavyTruck);
    EXPECT_EQ(t.vehicle.empty.mass_kg, rigid.vehicle.empty.mass_kg);
    EXPECT_DOUBLE_EQ(t.max_mass_kg, kTractorCombinationMaxKg);
    EXPECT_DOUBLE_EQ(t.vehicle.empty.mass_kg + t.payload_capacity_kg, t.max_mass_kg);
    DrawnVehicle parsed;
    std::string error;
    ASSERT_TRUE(parse_vehicle_id(t.id, &parsed, &error)) << error;
    EXPECT_EQ(parsed.id, t.id);
    EXPECT_EQ(describe_vehicle(parsed), describe_vehicle(t));
  }
  EXPECT_EQ(trucks[0].id, "tractor-" + std::to_string(kTruckFirstSeed));
  DrawnVehicle parsed;
  std::string error;
  EXPECT_FALSE(parse_vehicle_id("tractor-x1", &parsed, &error));
  EXPECT_NE(error.find("seed"), std::string::npos);
}

// J1939's EEC1 carries the engine speed on every truck, whatever its torque signal; with a gear
// number on the bus the engineer has the gearbox's datasheet too (its ratios and converter map),
// which tell a slipping converter from the engine speed.
TEST(SimTruckPopulation, EveryTractorsBusCarriesTheEngineSpeed) {
  int wheel_torque_automatics = 0;
  for (const DrawnVehicle& t : draw_truck_population(40, kTruckFirstSeed)) {
    ASSERT_TRUE(bus_has_engine_speed(t)) << t.id;
    const std::string can = VehicleBus(t).can_config_yaml("v.dbc");
    EXPECT_NE(can.find("engine_speed:"), std::string::npos) << t.id;
    if (t.sensors.torque != TorqueSignal::kWheelTorque || !t.sensors.gear_index) continue;
    const std::string config =
        datasheet_config_yaml(t, Realism::all(), Knowledge::kKnownScale, "v.dbc");
    EXPECT_NE(config.find("gear_ratios:"), std::string::npos) << t.id;
    if (!t.vehicle.powertrain.has_torque_converter()) continue;
    ++wheel_torque_automatics;
    EXPECT_NE(config.find("torque_converter_stall_torque_ratio:"), std::string::npos) << t.id;
  }
  EXPECT_GT(wheel_torque_automatics, 0);
  // A car keeps the bus it was drawn with.
  for (const DrawnVehicle& d : draw_population(14, 1)) {
    if (d.vehicle_class == VehicleClass::kHeavyTruck) continue;
    EXPECT_EQ(bus_has_engine_speed(d), d.sensors.torque == TorqueSignal::kEngineTorque) << d.id;
  }
}

TEST(SimTruckPopulation, TruckDrivesAreNotInTheCarSuite) {
  const std::vector<std::string> cars = population_scenario_names();
  const std::vector<std::string> trucks = truck_scenario_names();
  for (const std::string& c : cars) EXPECT_EQ(c.rfind("truck_", 0), std::string::npos) << c;
  const std::set<std::string> truck_set(trucks.begin(), trucks.end());
  for (const std::string& c : cars) EXPECT_EQ(truck_set.count(c), 1U) << c;
  EXPECT_EQ(trucks.size(), cars.size() + 5);
  for (const DrawnVehicle& d : draw_truck_population(20, kTruckFirstSeed)) {
    for (const std::string& name : trucks) {
      PopulationRun run;
      EXPECT_EQ(make_population_run(d, name, 1, Realism::all(), &run), "") << d.id << name;
      EXPECT_FALSE(population_scenario_description(name).empty()) << name;
      EXPECT_LE(run.physics.mass_at(0.0).mass_kg, d.max_mass_kg * 1.05) << d.id << " " << name;
    }
  }
}

// The wheel torque the prime mover's torque or power limit allows in that gear at that speed.
double limit_nm(const PowertrainParams& p, double radius_m, const TruthRow& t) {
  const double ratio = p.gear_ratios[static_cast<std::size_t>(t.gear - 1)] * p.final_drive_ratio;
  const double engine_radps = t.speed_mps / radius_m * ratio;
  return std::min(p.max_torque_nm, p.max_power_w / engine_radps) * ratio * p.efficiency;
}

// Floored from rest: 10-40 s after the start, the torque mostly sits at its limit.
TEST(SimTruckPopulation, LaunchHoldsTheTorqueAtItsLimit) {
  const DrawnVehicle d = draw_tractor(kTruckFirstSeed);
  PopulationRun run;
  const SimulationResult r = simulate_run(d, "truck_launch_flat", &run);
  const PowertrainParams& p = run.physics.vehicle.powertrain;
  int in_gear = 0, at_limit = 0;
  for (const TruthRow& t : r.truth) {
    if (t.time_us < 10'000'000 || t.time_us > 40'000'000 || t.gear == 0) continue;
    ++in_gear;
    if (t.wheel_torque_nm > 0.9 * limit_nm(p, r.vehicle.wheel_radius_m, t)) ++at_limit;
  }
  ASSERT_GT(in_gear, 1000);
  EXPECT_GT(at_limit, in_gear * 2 / 3);  // the rest: the torque ramping back after a shift
}

TEST(SimTruckPopulation, OneGearDriveNeverShiftsNorBrakes) {
  const DrawnVehicle d = draw_tractor(kTruckFirstSeed + 2);
  PopulationRun run;
  const SimulationResult r = simulate_run(d, "truck_one_gear_rolling", &run);
  const int held = run.physics.vehicle.powertrain.hold_gear;
  ASSERT_GT(held, 1);
  for (const TruthRow& t : r.truth) {
    ASSERT_EQ(t.gear, held) << t.time_us;
    ASSERT_EQ(t.brake_pressure_pa, 0.0) << t.time_us;
  }
  const auto [lo, hi] = std::minmax_element(
      r.truth.begin(), r.truth.end(),
      [](const TruthRow& a, const TruthRow& b) { return a.speed_mps < b.speed_mps; });
  EXPECT_GT(hi->speed_mps - lo->speed_mps, 5.0);  // floored, then drifting on the hills
}

// As a partner's recordings: floored 30-60 s in its one gear, then the speed controller holds
// the speed reached, its torque well off the limit, so the drive has a change of force in it.
TEST(SimTruckPopulation, OneGearDriveIsFlooredThenCruisesAtTheSpeedReached) {
  const DrawnVehicle d = draw_tractor(kTruckFirstSeed);
  PopulationRun run;
  const SimulationResult r = simulate_run(d, "truck_one_gear_flat", &run);
  const PowertrainParams& p = run.physics.vehicle.powertrain;
  const double radius_m = r.vehicle.wheel_radius_m;
  const auto at = [&](double t_s) {
    return *std::find_if(r.truth.begin(), r.truth.end(), [&](const TruthRow& t) {
      return static_cast<double>(t.time_us) >= t_s * 1e6;
    });
  };
  for (const double t_s : {5.0, 15.0, 29.0}) {
    const TruthRow t = at(t_s);
    EXPECT_GT(t.wheel_torque_nm, 0.95 * limit_nm(p, radius_m, t)) << t_s;
  }
  const double cruise_mps = at(70.0).speed_mps;
  for (const double t_s : {70.0, 120.0, 180.0, 235.0}) {
    const TruthRow t = at(t_s);
    EXPECT_LT(t.wheel_torque_nm, 0.9 * limit_nm(p, radius_m, t)) << t_s;
    EXPECT_NEAR(t.speed_mps, cruise_mps, 0.5) << t_s;
  }
  EXPECT_GT(cruise_mps, at(0.0).speed_mps + 2.0);
}

// The trailer arrives and leaves while the tractor stands, and weighs 100-200 % of it.
TEST(SimTruckPopulation, CouplingAddsATrailerAtAStopAndRemovesItAtAnother) {
  const DrawnVehicle d = draw_tractor(kTruckFirstSeed + 3);
  PopulationRun run;
  const SimulationResult r = simulate_run(d, "truck_coupling", &run);
  const double solo = r.truth.front().mass_kg;
  const double loaded =
      std::max_element(r.truth.begin(), r.truth.end(), [](const TruthRow& a, const TruthRow& b) {
        return a.mass_kg < b.mass_kg;
      })->mass_kg;
  EXPECT_GE(loaded - solo, 0.99 * d.vehicle.empty.mass_kg);
  EXPECT_LE(loaded - solo, 2.01 * d.vehicle.empty.mass_kg);
  EXPECT_NEAR(r.truth.back().mass_kg, solo, 1e-6 * solo);
  for (std::size_t k = 1; k < r.truth.size(); ++k) {
    if (r.truth[k].mass_kg != r.truth[k - 1].mass_kg) {
      ASSERT_LT(r.truth[k].speed_mps, 0.05) << r.truth[k].time_us;
    }
  }
}

}  // namespace
}  // namespace vmass::sim

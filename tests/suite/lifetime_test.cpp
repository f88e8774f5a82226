// A car's Nth drive through the daemon's state file (tools/vmass_suite/lifetime_run.hpp): five
// drives with the same load, then half the payload capacity put in the boot while parked. The
// sixth drive, restored from the file the fifth saved, must see the new load as well as the
// same drive replayed fresh does, with and without the deflection sensor, and its interval
// must hold the truth: yesterday's pairs are no evidence of today's load.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "lifetime_run.hpp"
#include "vmass/sim/lifetime.hpp"
#include "vmass/sim/population.hpp"
#include "vmass/sim/truck_population.hpp"

namespace vmass::suite {
namespace {

namespace fs = std::filesystem;

// The first SUV that reads its load with a passive rear axle and has every other input.
sim::DrawnVehicle suv_with_a_load_sensor() {
  for (std::uint64_t seed = 1; seed < 1000; ++seed) {
    const sim::DrawnVehicle v = sim::draw_vehicle(sim::VehicleClass::kSuv, seed);
    const sim::VehicleSensors& s = v.sensors;
    if (s.deflection && !v.vehicle.rear_levelling && s.brake_pressure && s.lateral &&
        s.torque == sim::TorqueSignal::kWheelTorque && s.speed == sim::SpeedSignal::kEsc) {
      return v;
    }
  }
  return sim::draw_vehicle(sim::VehicleClass::kSuv, 1);
}

std::vector<sim::LifetimeDrive> five_drives_then_a_loaded_boot(const sim::DrawnVehicle& v) {
  const double l = v.vehicle.wheelbase_m;
  const std::vector<sim::LoadItem> two_people = {{80.0, 0.45 * l, 0.37, 0.55},
                                                 {70.0, 0.45 * l, -0.37, 0.55}};
  std::vector<sim::LifetimeDrive> plan;
  const char* scenarios[] = {"paper_exp2_eps1", "urban",           "highway",
                             "mountain",        "paper_exp1_eps1", "paper_exp2_eps1"};
  for (int i = 1; i <= 6; ++i) {
    sim::LifetimeDrive d;
    d.index = i;
    d.scenario = scenarios[i - 1];
    d.seed = 40 + static_cast<std::uint64_t>(i);
    d.payload = two_people;
    plan.push_back(d);
  }
  const double boot_kg = 0.5 * v.payload_capacity_kg;
  plan.back().payload.push_back({boot_kg, l + 0.45, 0.0, 0.75});
  plan.back().load_change = "boot loaded";
  plan.back().payload_change_kg = boot_kg;
  return plan;
}

TEST(Lifetime, ALoadAddedWhileParkedIsSeenThroughTheStateFile) {
  const sim::DrawnVehicle vehicle = suv_with_a_load_sensor();
  ASSERT_TRUE(vehicle.sensors.deflection) << "no SUV of the population reads its load";
  LifetimeSpec spec;
  spec.vehicle_id = vehicle.id;
  spec.plan = five_drives_then_a_loaded_boot(vehicle);
  spec.knowledge = {sim::Knowledge::kKnownScale};
  const fs::path work = fs::temp_directory_path() / ("vmass_lifetime_test_" + vehicle.id);
  fs::create_directories(work);
  const LifetimeResult result = run_lifetime(spec, work.string());
  fs::remove_all(work);
  ASSERT_EQ(result.error, "");

  // drive 6's rows: [deflection sensor][lifetime or fresh]
  nlohmann::json last[2][2];
  std::istringstream lines(result.json_lines);
  for (std::string line; std::getline(lines, line);) {
    const nlohmann::json j = nlohmann::json::parse(line);
    if (j["drive"] != 6) continue;
    last[j["deflection_sensor"] ? 1 : 0][j["mode"] == "lifetime" ? 0 : 1] = j;
  }
  for (int sensor : {1, 0}) {
    SCOPED_TRACE(sensor ? "with the deflection sensor" : "without it");
    const nlohmann::json& life = last[sensor][0];
    const nlohmann::json& fresh = last[sensor][1];
    ASSERT_TRUE(life.contains("final_error_pct") && fresh.contains("final_error_pct"));
    EXPECT_TRUE(life["restored"].get<bool>());
    const double life_error = std::abs(life["final_error_pct"].get<double>());
    const double fresh_error = std::abs(fresh["final_error_pct"].get<double>());
    std::cout << (sensor ? "with" : "without") << " sensor: drive 6 ends " << life_error
              << " % off through the state file, " << fresh_error << " % fresh; covered "
              << life["covered_end"] << " / " << fresh["covered_end"] << ", converged then outside "
              << life["converged_outside_fraction"] << " / " << fresh["converged_outside_fraction"]
              << ", covered at 20 s " << life["covered_20s"] << " / " << fresh["covered_20s"]
              << ", " << life["vehicle"] << "\n";
    EXPECT_LE(life_error, fresh_error + 1.0);
    EXPECT_GE(life["covered_20s"].get<int>(), fresh["covered_20s"].get<int>());
    EXPECT_EQ(life["covered_end"], 1);
    const nlohmann::json& outside = life["converged_outside_fraction"];
    EXPECT_TRUE(outside.is_null() || outside.get<double>() <= 0.2) << outside;
  }
}

// New tyres (vmass-suite --tyre-change-drive) change the car from their drive on, and nothing
// else: the life's drives and loads are those of the life without them.
TEST(Lifetime, NewTyresComeBeforeTheirDriveAndLeaveTheLifeAsItWas) {
  const sim::DrawnVehicle vehicle = sim::draw_vehicle(sim::VehicleClass::kVan, 5);
  const std::vector<sim::LifetimeDrive> plain = sim::plan_lifetime(vehicle, 10, 2);
  const std::vector<sim::LifetimeDrive> tyres = sim::plan_lifetime(vehicle, 10, 2, 6);
  ASSERT_EQ(plain.size(), tyres.size());
  const double factor = tyres.back().tyre_radius_factor;
  EXPECT_GE(factor, 1.01);
  EXPECT_LE(factor, 1.03);
  for (std::size_t i = 0; i < plain.size(); ++i) {
    SCOPED_TRACE("drive " + std::to_string(i + 1));
    EXPECT_EQ(plain[i].scenario, tyres[i].scenario);
    EXPECT_EQ(plain[i].seed, tyres[i].seed);
    EXPECT_EQ(plain[i].load_change, tyres[i].load_change);
    EXPECT_DOUBLE_EQ(sim::payload_mass_kg(plain[i].payload),
                     sim::payload_mass_kg(tyres[i].payload));
    EXPECT_DOUBLE_EQ(plain[i].tyre_radius_factor, 1.0);
    EXPECT_DOUBLE_EQ(tyres[i].tyre_radius_factor, i + 1 < 6 ? 1.0 : factor);
    EXPECT_EQ(tyres[i].car_change.empty(), i + 1 != 6) << tyres[i].car_change;
  }
  EXPECT_NE(tyres[5].car_change.find("new tyres (radius +"), std::string::npos);

  // The tyres turn slower for the same speed: the ESC, which assumes the old radius, reads low.
  sim::TrueVehicle car = vehicle.vehicle;
  car.wheel_speed.radius_error_fraction = 0.01;
  const double radius_m = car.wheel_radius_m;
  sim::fit_tyres(1.02, &car);
  EXPECT_DOUBLE_EQ(car.wheel_radius_m, 1.02 * radius_m);
  EXPECT_NEAR(car.wheel_speed.radius_error_fraction, 1.01 / 1.02 - 1.0, 1e-12);
}

// Another trailer (vmass-suite --trailer-change-drive) is coupled before its drive: another
// load on the fifth wheel, the combination's drag area and rolling coefficient scaled from then
// on; the drives before it are the life's without. A car pulls no trailer: its life is as it was.
TEST(Lifetime, AnotherTrailerComesBeforeItsDriveWithItsLoadAndResistances) {
  const sim::DrawnVehicle tractor = sim::draw_truck_population(1, sim::kTruckFirstSeed).front();
  ASSERT_TRUE(tractor.tractor);
  const std::vector<sim::LifetimeDrive> plain = sim::plan_lifetime(tractor, 10, 3);
  const std::vector<sim::LifetimeDrive> swapped = sim::plan_lifetime(tractor, 10, 3, 0, 6);
  ASSERT_EQ(plain.size(), swapped.size());
  for (std::size_t i = 0; i < 5; ++i) {
    EXPECT_EQ(plain[i].load_change, swapped[i].load_change);
    EXPECT_DOUBLE_EQ(sim::payload_mass_kg(plain[i].payload),
                     sim::payload_mass_kg(swapped[i].payload));
    EXPECT_DOUBLE_EQ(swapped[i].trailer_drag_factor, 1.0);
    EXPECT_TRUE(swapped[i].car_change.empty());
  }
  const sim::LifetimeDrive& sixth = swapped[5];
  EXPECT_EQ(sixth.load_change.rfind("another trailer (", 0), 0u) << sixth.load_change;
  EXPECT_NE(sixth.car_change.find("another trailer (drag area "), std::string::npos);
  // A change worth the name: at least a tenth of the payload capacity.
  EXPECT_GE(std::abs(sixth.payload_change_kg), 0.1 * (tractor.payload_capacity_kg - 100.0));
  EXPECT_GE(sixth.trailer_drag_factor, 0.75);
  EXPECT_LE(sixth.trailer_drag_factor, 1.3);
  EXPECT_GE(sixth.trailer_rolling_factor, 0.85);
  EXPECT_LE(sixth.trailer_rolling_factor, 1.2);
  for (std::size_t i = 5; i < swapped.size(); ++i) {
    EXPECT_EQ(swapped[i].trailer_drag_factor, sixth.trailer_drag_factor);
    EXPECT_EQ(swapped[i].trailer_rolling_factor, sixth.trailer_rolling_factor);
    EXPECT_EQ(swapped[i].scenario, plain[i].scenario);
  }
  sim::TrueVehicle combination = tractor.vehicle;
  sim::couple_trailer(1.2, 0.9, &combination);
  EXPECT_DOUBLE_EQ(combination.drag_area_m2, 1.2 * tractor.vehicle.drag_area_m2);
  EXPECT_DOUBLE_EQ(combination.rolling_resistance_coeff,
                   0.9 * tractor.vehicle.rolling_resistance_coeff);

  const sim::DrawnVehicle van = sim::draw_vehicle(sim::VehicleClass::kVan, 5);
  const std::vector<sim::LifetimeDrive> van_life = sim::plan_lifetime(van, 10, 2, 0, 6);
  for (const sim::LifetimeDrive& d : van_life) EXPECT_EQ(d.trailer_drag_factor, 1.0);
}

}  // namespace
}  // namespace vmass::suite

// The registered scenarios do what their descriptions promise.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "sim_test_util.hpp"

namespace vmass::sim {
namespace {

using test::ideal;
using test::run;

constexpr double kDeg = 3.14159265358979323846 / 180.0;

TEST(SimScenarios, RegistryHasTheFourScenarios) {
  const std::vector<std::string> names = scenario_names();
  EXPECT_EQ(names, (std::vector<std::string>{"paper_exp1", "paper_exp2", "load_step", "steady_turn",
                                             "static_ballast"}));
  for (const std::string& n : names) {
    const auto s = find_scenario(n);
    ASSERT_TRUE(s.has_value()) << n;
    EXPECT_EQ(s->name, n);
    EXPECT_EQ(s->validate(), "") << n;
    EXPECT_FALSE(s->description.empty());
    EXPECT_EQ(s->tick_rate_hz, 100.0);
  }
  EXPECT_FALSE(find_scenario("paper_exp3").has_value());
}

void expect_standstill_start(const SimulationResult& r, double until_s) {
  for (std::size_t k = 0; k < r.truth.size() && to_seconds(r.truth[k].time_us) < until_s; ++k) {
    EXPECT_TRUE(r.truth[k].stopped);
    EXPECT_EQ(r.samples[k].speed_mps, 0.0);
  }
}

TEST(SimScenarios, PaperExp1IsAStraightUrbanCycleOnSlopes) {
  const SimulationResult r = run(*find_scenario("paper_exp1"), ideal());
  EXPECT_EQ(r.truth.size(), 20001u);
  expect_standstill_start(r, 5.0);
  double vmax = 0.0, gmin = 0.0, gmax = 0.0;
  for (const TruthRow& t : r.truth) {
    EXPECT_EQ(t.mass_kg, 1659.0);
    EXPECT_EQ(t.accel_y_mps2, 0.0);
    EXPECT_EQ(t.yaw_rate_radps, 0.0);
    vmax = std::max(vmax, t.speed_mps);
    gmin = std::min(gmin, t.grade_rad);
    gmax = std::max(gmax, t.grade_rad);
  }
  EXPECT_NEAR(vmax, 50.0 / 3.6, 0.5);  // ECE-15 top speed
  EXPECT_LT(gmin, -0.025);
  EXPECT_GT(gmax, 0.035);
  EXPECT_LT(std::max(-gmin, gmax), 0.05);
}

TEST(SimScenarios, PaperExp2CornersAtModerateLateralAcceleration) {
  const SimulationResult r = run(*find_scenario("paper_exp2"), ideal());
  expect_standstill_start(r, 5.0);
  std::vector<double> ay;
  int big_steer = 0;
  double ax_lo = 0.0, ax_hi = 0.0;
  for (const TruthRow& t : r.truth) {
    ay.push_back(std::abs(t.accel_y_mps2));
    if (std::abs(t.steering_wheel_angle_rad) > 15.0 * kDeg) ++big_steer;
    ax_lo = std::min(ax_lo, t.accel_x_mps2);
    ax_hi = std::max(ax_hi, t.accel_x_mps2);
    EXPECT_EQ(t.mass_kg, 1659.0);
  }
  std::sort(ay.begin(), ay.end());
  EXPECT_LT(ay.back(), 4.0);
  EXPECT_LT(ay[ay.size() * 99 / 100], 3.5);
  EXPECT_GT(ay.back(), 2.5);
  EXPECT_GT(static_cast<double>(big_steer) / static_cast<double>(r.truth.size()), 0.2);
  EXPECT_LT(ax_lo, -1.5);
  EXPECT_GT(ax_hi, 1.5);
}

TEST(SimScenarios, LoadStepAdds250KgWhileStanding) {
  const SimulationResult r = run(*find_scenario("load_step"), ideal());
  expect_standstill_start(r, 5.0);
  EXPECT_EQ(r.truth.front().mass_kg, 1659.0);
  EXPECT_EQ(r.truth.back().mass_kg, 1909.0);
  double first_change = -1.0, last_change = -1.0;
  for (std::size_t k = 1; k < r.truth.size(); ++k) {
    if (r.truth[k].mass_kg != r.truth[k - 1].mass_kg) {
      EXPECT_TRUE(r.truth[k].stopped);
      const double t = to_seconds(r.truth[k].time_us);
      if (first_change < 0.0) first_change = t;
      last_change = t;
    }
  }
  EXPECT_GT(first_change, 60.0);
  EXPECT_LT(last_change, 80.0);
  // Standing ~10 s loaded before driving on, about 60 s of driving on each side
  double stand_start = 0.0, stand_end = 0.0;
  for (const TruthRow& t : r.truth) {
    const double ts = to_seconds(t.time_us);
    if (ts > 30.0 && ts < first_change && !t.stopped) stand_start = ts;
    if (ts > last_change && t.stopped) stand_end = ts;
    if (ts > last_change && !t.stopped) break;
  }
  EXPECT_GT(stand_end - last_change, 7.0);
  EXPECT_GT(stand_start, 60.0);
  // The deflection steps up: compare standing before and after (same place)
  const double before =
      r.truth[static_cast<std::size_t>(first_change * 100) - 10].rear_right_deflection_m;
  const double after =
      r.truth[static_cast<std::size_t>(last_change * 100) + 500].rear_right_deflection_m;
  EXPECT_GT(after - before, 0.02);
}

TEST(SimScenarios, SteadyTurnKeeps15MetresPerSecond) {
  const SimulationResult r = run(*find_scenario("steady_turn"), ideal());
  for (const TruthRow& t : r.truth) {
    EXPECT_NEAR(t.speed_mps, 15.0, 0.1);
    EXPECT_FALSE(t.stopped);
  }
}

TEST(SimScenarios, InvalidScenariosAreRejectedWithAMessage) {
  Scenario s = *find_scenario("steady_turn");
  s.integration_rate_hz = 950.0;
  SimulationResult r;
  EXPECT_NE(simulate(s, {}, &r).find("integration_rate_hz"), std::string::npos);
  s = *find_scenario("steady_turn");
  s.vehicle.wheel_radius_m = -1.0;
  EXPECT_NE(simulate(s, {}, &r).find("wheel_radius_m"), std::string::npos);
  s = *find_scenario("steady_turn");
  s.road.grade_rad = PiecewiseLinear({{0, 0}, {-5, 0.01}});
  EXPECT_NE(simulate(s, {}, &r).find("road.grade_rad"), std::string::npos);
  EXPECT_NE(simulate(*find_scenario("steady_turn"), {}, nullptr), "");
}

TEST(SimScenarios, MassAtMatchesAddPayload) {
  const Scenario s = *find_scenario("load_step");
  std::vector<LoadItem> all = s.initial_payload;
  for (const LoadItem& it : s.load_changes.front().items) all.push_back(it);
  const MassProperties a = add_payload(s.vehicle.empty, all);
  const MassProperties b = s.mass_at(1000.0);
  EXPECT_NEAR(a.mass_kg, b.mass_kg, 1e-9);
  EXPECT_NEAR(a.cg_x_m, b.cg_x_m, 1e-12);
  EXPECT_NEAR(a.cg_y_m, b.cg_y_m, 1e-12);
  EXPECT_NEAR(a.cg_z_m, b.cg_z_m, 1e-12);
  EXPECT_NEAR(a.yaw_inertia_kgm2, b.yaw_inertia_kgm2, 1e-7);
  // The centre of gravity moves back and to the right with the rear/right passengers
  const MassProperties before = s.mass_at(0.0);
  EXPECT_GT(b.cg_x_m, before.cg_x_m);
  EXPECT_LT(b.cg_y_m, before.cg_y_m);
  EXPECT_GT(b.yaw_inertia_kgm2, before.yaw_inertia_kgm2);
}

}  // namespace
}  // namespace vmass::sim

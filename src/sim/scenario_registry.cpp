// The named scenarios of vmass-sim. Each is built from data below; see scenario.hpp.
#include <cmath>
#include <functional>
#include <utility>

#include "paper_roads.hpp"
#include "vmass/sim/scenario.hpp"
#include "vmass/sim/static_ballast.hpp"

namespace vmass::sim {

namespace {

constexpr double kDeg = 3.14159265358979323846 / 180.0;
constexpr double kKmh = 1.0 / 3.6;

// Points (x, y) with y scaled (units to SI).
PiecewiseLinear scaled(std::vector<PiecewiseLinear::Point> pts, double scale) {
  for (auto& p : pts) p.y *= scale;
  return PiecewiseLinear(std::move(pts));
}

// Driver, a front passenger's worth of luggage: 159 kg on top of the 1500 kg empty car, so
// 1659 kg as in the paper's experiments. The driver sits left (left-hand drive), one passenger
// behind him, a bag in the boot: the rear-right corner gets less than a quarter of it.
std::vector<LoadItem> paper_payload() {
  return {
      {80.0, 1.30, 0.37, 0.60},  // driver
      {65.0, 2.00, 0.40, 0.62},  // rear-left passenger
      {14.0, 3.10, 0.00, 0.70},  // bag in the boot
  };
}

Scenario base(std::string name, std::string description, double duration_s) {
  Scenario s;
  s.name = std::move(name);
  s.description = std::move(description);
  s.duration_s = duration_s;
  s.initial_payload = paper_payload();
  s.default_noise = NoiseSet::kEps1;
  return s;
}

Scenario paper_exp1() {
  Scenario s = base("paper_exp1",
                    "ECE-15-like urban cycle (0-50 km/h) on a straight road with slopes of "
                    "-3..+4 %, 1659 kg, 200 s",
                    200.0);
  // ECE-15 elementary urban cycle (speeds in km/h), its first idle cut to 5 s, the end
  // padded with standstill to 200 s.
  s.driver.speed_mps =
      scaled({{0, 0},    {5, 0},    {9, 15},   {17, 15},  {22, 0},   {43, 0},   {48, 15},
              {50, 15},  {55, 32},  {79, 32},  {87, 10},  {90, 0},   {111, 0},  {116, 15},
              {118, 15}, {127, 35}, {129, 35}, {137, 50}, {149, 50}, {157, 35}, {170, 35},
              {172, 35}, {179, 10}, {182, 0},  {200, 0}},
             kKmh);
  s.road = paper_exp1_road();
  return s;
}

Scenario paper_exp2() {
  Scenario s = base("paper_exp2",
                    "accelerating, braking, slaloms and constant-radius turns (|a_y| mostly "
                    "< 3.5 m/s^2), 1659 kg, 200 s",
                    200.0);
  s.driver.speed_mps = PiecewiseLinear({{0, 0},
                                        {5, 0},
                                        {13, 14},
                                        {33, 14},
                                        {37, 8},
                                        {45, 16},
                                        {70, 16},
                                        {75, 10},
                                        {90, 10},
                                        {96, 18},
                                        {125, 18},
                                        {130, 12},
                                        {150, 12},
                                        {154, 15},
                                        {175, 15},
                                        {182, 0},
                                        {200, 0}});
  s.driver.steering_wheel_angle_rad = scaled({{0, 0},
                                              {47, 0},
                                              {50, 32},
                                              {64, 32},
                                              {67, 0},  // left turn, 16 m/s
                                              {77, 0},
                                              {80, -55},
                                              {87, -55},
                                              {90, 0},  // right turn, 10 m/s
                                              {133, 0},
                                              {136, 45},
                                              {144, 45},
                                              {147, 0}},  // left turn, 12 m/s
                                             kDeg);
  s.driver.steering_sines = {
      {15.0, 31.0, 45.0 * kDeg, 0.35},    // slalom at 14 m/s
      {100.0, 122.0, 25.0 * kDeg, 0.25},  // slalom at 18 m/s
      {157.0, 173.0, 35.0 * kDeg, 0.40},  // slalom at 15 m/s
  };
  s.road = paper_exp2_road();
  return s;
}

Scenario load_step() {
  Scenario s = base(
      "load_step", "drive 60 s, stop, +250 kg while standing (1659 -> 1909 kg), drive 60 s", 150.0);
  // First drive 5..68 s, standstill 68..82 s with the load going in at 71..74 s, second drive
  // 82..145 s, the same pattern again.
  s.driver.speed_mps =
      PiecewiseLinear({{0, 0},    {5, 0},    {13, 14},  {25, 14},  {30, 8},  {38, 16},  {50, 16},
                       {58, 10},  {60, 10},  {68, 0},   {82, 0},   {90, 14}, {102, 14}, {107, 8},
                       {115, 16}, {127, 16}, {135, 10}, {137, 10}, {145, 0}, {150, 0}});
  s.driver.steering_wheel_angle_rad = scaled({{0, 0},
                                              {15, 0},
                                              {17, 35},
                                              {22, 35},
                                              {24, 0},  // left turn, 14 m/s
                                              {92, 0},
                                              {94, 35},
                                              {99, 35},
                                              {101, 0}},  // the same after loading
                                             kDeg);
  s.driver.steering_sines = {
      {40.0, 48.0, 30.0 * kDeg, 0.30},
      {117.0, 125.0, 30.0 * kDeg, 0.30},
  };
  // Front passenger, two rear passengers, a bag: the rear right gets much more than a quarter.
  LoadChange step;
  step.start_s = 71.0;
  step.duration_s = 3.0;
  step.items = {
      {80.0, 1.30, -0.37, 0.60},  // front passenger
      {75.0, 2.00, 0.40, 0.62},   // rear left
      {75.0, 2.00, -0.40, 0.62},  // rear right
      {20.0, 3.10, 0.00, 0.70},   // bag
  };
  s.load_changes = {step};
  s.road.grade_rad =
      slope_percent({{0, 0}, {100, 0}, {250, 2}, {450, 2}, {600, -1}, {800, -1}, {900, 0}});
  return s;
}

Scenario steady_turn() {
  Scenario s =
      base("steady_turn",
           "15 m/s on a left circle of 80 m radius, flat road (a_y = 2.81 m/s^2), 60 s", 60.0);
  s.initial_speed_mps = 15.0;
  s.driver.speed_mps = PiecewiseLinear(15.0);
  s.driver.circle = CircleCourse{80.0, true};
  return s;
}

const std::vector<std::pair<const char*, std::function<Scenario()>>>& registry() {
  static const std::vector<std::pair<const char*, std::function<Scenario()>>> r = {
      {"paper_exp1", paper_exp1},
      {"paper_exp2", paper_exp2},
      {"load_step", load_step},
      {"steady_turn", steady_turn},
      {"static_ballast", [] { return static_ballast_scenario(); }},
  };
  return r;
}

}  // namespace

std::vector<std::string> scenario_names() {
  std::vector<std::string> out;
  for (const auto& [name, make] : registry()) out.emplace_back(name);
  return out;
}

std::optional<Scenario> find_scenario(std::string_view name) {
  for (const auto& [n, make] : registry()) {
    if (name == n) return make();
  }
  return std::nullopt;
}

}  // namespace vmass::sim

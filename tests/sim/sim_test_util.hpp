// Helpers shared by the simulator tests: small scenarios with known answers.
#pragma once

#include <cmath>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "vmass/sim/scenario.hpp"
#include "vmass/sim/simulator.hpp"

namespace vmass::sim::test {

inline std::string read_file(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  std::ostringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

inline std::string source_path(const std::string& rel) {
  return std::string(VMASS_SOURCE_DIR) + "/" + rel;
}

/// A straight, flat road, the paper's 1659 kg car, no steering, holding speed_mps from the
/// start (0: standing the whole time).
inline Scenario straight_scenario(double speed_mps, double duration_s) {
  Scenario s = *find_scenario("paper_exp1");
  s.name = "test_straight";
  s.duration_s = duration_s;
  s.initial_speed_mps = speed_mps;
  s.driver = DriverProfile{};
  s.driver.speed_mps = PiecewiseLinear(speed_mps);
  s.road = Road{};
  return s;
}

inline SimulationResult run(const Scenario& s, SimulationOptions o = {}) {
  SimulationResult r;
  const std::string err = simulate(s, o, &r);
  if (!err.empty()) throw std::runtime_error(err);
  return r;
}

inline SimulationOptions ideal() {
  SimulationOptions o;
  o.ideal_sensors = true;
  o.noise = NoiseSet::kNone;
  return o;
}

inline double mean(const std::vector<double>& v) {
  double s = 0.0;
  for (double x : v) s += x;
  return v.empty() ? 0.0 : s / static_cast<double>(v.size());
}

inline double stddev(const std::vector<double>& v) {
  const double m = mean(v);
  double s = 0.0;
  for (double x : v) s += (x - m) * (x - m);
  return v.size() < 2 ? 0.0 : std::sqrt(s / static_cast<double>(v.size() - 1));
}

}  // namespace vmass::sim::test

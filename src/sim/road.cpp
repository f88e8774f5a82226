#include "vmass/sim/road.hpp"
#include "vmass/core/constants.hpp"

#include <algorithm>
#include <cmath>

namespace vmass::sim {

std::string Road::validate() const {
  if (auto m = grade_rad.validate("road.grade_rad"); !m.empty()) return m;
  if (auto m = bank_rad.validate("road.bank_rad"); !m.empty()) return m;
  for (const auto& p : grade_rad.points()) {
    if (std::abs(p.y) > 0.35) return "road.grade_rad: |grade| must be <= 0.35 rad";
  }
  for (const auto& p : bank_rad.points()) {
    if (std::abs(p.y) > 0.2) return "road.bank_rad: |bank| must be <= 0.2 rad";
  }
  if (auto m = roughness.validate("road.roughness"); !m.empty()) return m;
  if (auto m = friction.validate("road.friction"); !m.empty()) return m;
  for (const auto& p : roughness.points()) {
    if (!(p.y >= 0.0 && p.y <= 10.0)) return "road.roughness must be in [0, 10]";
  }
  for (const auto& p : friction.points()) {
    if (!(p.y > 0.05 && p.y <= 1.5)) return "road.friction must be in (0.05, 1.5]";
  }
  for (std::size_t i = 0; i < bumps.size(); ++i) {
    if (!(bumps[i].severity_mps2 >= 0.0 && bumps[i].severity_mps2 < 20.0)) {
      return "road.bumps: severity_mps2 must be in [0, 20)";
    }
    if (i > 0 && !(bumps[i].position_m > bumps[i - 1].position_m)) {
      return "road.bumps must be in increasing position";
    }
  }
  if (!(bump_length_m > 0.05)) return "road.bump_length_m must be > 0.05";
  return "";
}

double Road::bump_deceleration_mps2(double axle_distance_m, double speed_mps) const {
  constexpr double kFullSeverityAboveMps = 8.0;
  // Bumps are sorted: find the last one at or before the axle.
  auto it = std::upper_bound(bumps.begin(), bumps.end(), axle_distance_m,
                             [](double s, const SpeedBump& b) { return s < b.position_m; });
  if (it == bumps.begin()) return 0.0;
  const SpeedBump& b = *(it - 1);
  const double u = (axle_distance_m - b.position_m) / bump_length_m;
  if (u >= 1.0) return 0.0;
  const double speed_scale = std::min(1.0, std::abs(speed_mps) / kFullSeverityAboveMps);
  return b.severity_mps2 * speed_scale * std::sin(kPi * u);
}

double grade_from_percent(double percent) { return std::atan(percent / 100.0); }

}  // namespace vmass::sim

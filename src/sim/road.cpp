#include "vmass/sim/road.hpp"

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
  return "";
}

double grade_from_percent(double percent) { return std::atan(percent / 100.0); }

}  // namespace vmass::sim

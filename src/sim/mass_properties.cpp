#include "vmass/sim/mass_properties.hpp"

#include <cmath>

namespace vmass::sim {

std::string MassProperties::validate(const std::string& prefix) const {
  if (!(mass_kg > 0.0) || !std::isfinite(mass_kg)) return prefix + "mass_kg must be > 0";
  if (!std::isfinite(cg_x_m) || !std::isfinite(cg_y_m)) return prefix + "cg_x_m/cg_y_m not finite";
  if (!(cg_z_m > 0.0) || !std::isfinite(cg_z_m)) return prefix + "cg_z_m must be > 0";
  if (!(yaw_inertia_kgm2 > 0.0) || !std::isfinite(yaw_inertia_kgm2)) {
    return prefix + "yaw_inertia_kgm2 must be > 0";
  }
  return "";
}

MassProperties add_payload(const MassProperties& empty, const std::vector<LoadItem>& items) {
  MassProperties out = empty;
  double m = empty.mass_kg;
  double mx = empty.mass_kg * empty.cg_x_m;
  double my = empty.mass_kg * empty.cg_y_m;
  double mz = empty.mass_kg * empty.cg_z_m;
  for (const LoadItem& it : items) {
    if (!(it.mass_kg > 0.0)) continue;
    m += it.mass_kg;
    mx += it.mass_kg * it.x_m;
    my += it.mass_kg * it.y_m;
    mz += it.mass_kg * it.z_m;
  }
  out.mass_kg = m;
  out.cg_x_m = mx / m;
  out.cg_y_m = my / m;
  out.cg_z_m = mz / m;
  const auto sq = [](double v) { return v * v; };
  double iz = empty.yaw_inertia_kgm2 +
              empty.mass_kg * (sq(empty.cg_x_m - out.cg_x_m) + sq(empty.cg_y_m - out.cg_y_m));
  for (const LoadItem& it : items) {
    if (!(it.mass_kg > 0.0)) continue;
    iz += it.mass_kg * (sq(it.x_m - out.cg_x_m) + sq(it.y_m - out.cg_y_m));
  }
  out.yaw_inertia_kgm2 = iz;
  return out;
}

}  // namespace vmass::sim

// MassProperties: mass, centre of gravity and yaw inertia of the simulated car, and how a payload
// (people, luggage, ballast: point masses) moves them.
//
//   M = M_e + sum m_i
//   x_cg = (M_e x_e + sum m_i x_i) / M        (likewise y_cg, z_cg)
//   I_z = I_e + M_e ((x_e - x_cg)^2 + (y_e - y_cg)^2) + sum m_i ((x_i - x_cg)^2 + (y_i - y_cg)^2)
//
// x is measured rearward from the front axle (so x_cg is l_f), y to the left (ISO 8855), z up
// from the ground. Plain value types and pure functions; thread-safe.
#pragma once

#include <string>
#include <vector>

namespace vmass::sim {

struct MassProperties {
  double mass_kg = 1500.0;
  double cg_x_m = 1.20;  ///< l_f: centre of gravity behind the front axle
  double cg_y_m = 0.0;   ///< lateral offset, left positive
  double cg_z_m = 0.55;  ///< height above ground
  double yaw_inertia_kgm2 = 2400.0;

  std::string validate(const std::string& prefix) const;
};

/// A point mass carried by the car.
struct LoadItem {
  double mass_kg = 0.0;
  double x_m = 0.0;  ///< behind the front axle
  double y_m = 0.0;  ///< left positive
  double z_m = 0.6;  ///< height above ground
};

/// The loaded car: the empty body plus each item (items with zero mass are ignored).
MassProperties add_payload(const MassProperties& empty, const std::vector<LoadItem>& items);

}  // namespace vmass::sim

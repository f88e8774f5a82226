// LoadGeometry: how vmass-calibrate turns an added ballast mass into the added rear-right wheel
// force that compresses the instrumented spring (paper eq. 2):
//
//   dF_rr = dM g l_f / (2 l)
//
// l the wheelbase, l_f the centre of gravity to the front axle, g gravity. The paper's
// assumption, which the fit inherits: the ballast sits at the vehicle's centre of gravity (the
// added load is shared between the axles like the vehicle's own mass, l_f / l on the rear) and
// the rear axle's share is split equally between left and right. The static initialisation
// (eq. 3, StaticInitializer) makes the same assumption when it inverts a force into a mass,
//   dM = 2 l dF_rr / (l_f g),
// so a stiffness calibrated through this mapping reproduces the ballast masses exactly there.
//
// Plain value type; thread-safe to share read-only.
#pragma once

#include <string>

#include "vmass/core/vehicle_params.hpp"

namespace vmass::calibrate {

struct LoadGeometry {
  double wheelbase_m = 0.0;         ///< l (config key vehicle.wheelbase_m)
  double cg_to_front_axle_m = 0.0;  ///< l_f (vehicle.cg_to_front_axle_m)
  double gravity_mps2 = 9.80665;    ///< g (vehicle.gravity_mps2)

  static LoadGeometry from_vehicle(const VehicleParams& vehicle);

  /// dF_rr / dM = g l_f / (2 l), N per kg.
  double wheel_force_per_kg() const;
  /// dF_rr for an added mass, N.
  double wheel_force_n(double added_mass_kg) const { return added_mass_kg * wheel_force_per_kg(); }
  /// dM for an added rear-right wheel force, kg (the inverse, eq. 3).
  double added_mass_kg(double wheel_force_n) const { return wheel_force_n / wheel_force_per_kg(); }

  /// "" or a message naming the vehicle.* key and the violated bound.
  std::string validate() const;
};

}  // namespace vmass::calibrate

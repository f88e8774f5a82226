// NominalVehicle: what the engineer's datasheet says about the car (not the truth), the only
// vehicle knowledge a baseline may use. Plain value type; thread-safe to copy and read.
#pragma once

#include <string>

namespace vmass::baselines {

struct NominalVehicle {
  double empty_mass_kg = 0.0;
  double wheel_radius_m = 0.0;
  double brake_gain_n_per_pa = 0.0;  ///< K_brake; 0 = unknown (braking ticks then unusable)
  double rotating_mass_kg = 0.0;     ///< J / r^2 (baselines that model it may use it)
  double drag_area_m2 = 0.0;         ///< C_d A (Vahidi)
  double air_density_kg_per_m3 = 1.2;
  double rolling_resistance_coeff = 0.0;  ///< f_r (Vahidi)
  double gravity_mps2 = 9.80665;

  /// Empty when usable, else a message naming the key and the violated bound. A baseline built
  /// from an invalid NominalVehicle never reports a mass.
  std::string validate() const;
};

}  // namespace vmass::baselines

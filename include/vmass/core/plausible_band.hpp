// The masses vmass believes a vehicle can have: one band for the three places a mass leaves
// the estimator (what it publishes, what the daemon saves, what it restores), so that nothing
// it publishes is refused at the next start, and nothing it refuses was ever published.
//
//   [0.9 M_empty, 1.25 M_max]      when the config gives the maximum permissible mass;
//   [0.9 M_empty, 3 M_empty]       when it does not.
//
// The margins hold a light driver's car (the datasheet's empty mass often includes one) and an
// overloaded one; outside them the estimate says more about the config or a sensor than about
// the load (an empty deflection written as a ride height gives a negative mass).
#pragma once

#include "vmass/core/vehicle_params.hpp"

namespace vmass {

struct MassBand {
  double low_kg = 0.0;
  double high_kg = 0.0;
  /// False for NaN.
  bool contains(double kg) const { return kg >= low_kg && kg <= high_kg; }
};

MassBand plausible_mass_band(const VehicleParams& vehicle);

}  // namespace vmass

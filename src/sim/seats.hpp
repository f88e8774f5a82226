// Where a vehicle of the population carries its payload: the seats' and the boot's positions
// of a car, or the cargo area of a van, pickup or truck (x behind the front axle, z above
// ground). The population's scenarios and a vehicle's lifetime of drives place people,
// luggage and cargo there.
#pragma once

#include "vmass/sim/population.hpp"

namespace vmass::sim {

struct Seats {
  double front_x, rear_x, boot_x, cargo_x0, cargo_x1, seat_z, cargo_z;
  bool cargo;  ///< van, pickup, truck: a cargo area instead of seats and a boot
};

Seats seats_of(const DrawnVehicle& d);

}  // namespace vmass::sim

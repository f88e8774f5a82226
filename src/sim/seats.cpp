#include "seats.hpp"

namespace vmass::sim {

Seats seats_of(const DrawnVehicle& d) {
  const double l = d.vehicle.wheelbase_m;
  // A tractor's payload is the semi-trailer's load on the fifth wheel, just ahead of the tandem.
  if (d.tractor) return {0.02 * l, 0.02 * l, l, 0.80 * l, 0.95 * l, 1.8, 1.9, true};
  switch (d.vehicle_class) {
    case VehicleClass::kVan:
      return {0.10 * l, 0.10 * l, l + 0.4, 0.45 * l, l + 0.6, 0.9, 0.9, true};
    case VehicleClass::kPickup:
      return {0.35 * l, 0.60 * l, l + 0.4, 0.80 * l, l + 0.9, 0.9, 1.1, true};
    case VehicleClass::kHeavyTruck:
      return {0.02 * l, 0.02 * l, l, 0.25 * l, l + 1.5, 1.8, 1.9, true};
    default:
      return {0.45 * l, 0.78 * l, l + 0.45, 0.0, 0.0, 0.55, 0.75, false};
  }
}

}  // namespace vmass::sim

#include "vmass/sim/truck_population.hpp"

namespace vmass::sim {

DrawnVehicle draw_tractor(std::uint64_t vehicle_seed) {
  DrawnVehicle d = draw_vehicle(VehicleClass::kHeavyTruck, vehicle_seed);
  d.id = std::string(kTractorIdPrefix) + "-" + std::to_string(vehicle_seed);
  d.tractor = true;
  d.max_mass_kg = kTractorCombinationMaxKg;
  d.payload_capacity_kg = kTractorCombinationMaxKg - d.vehicle.empty.mass_kg;
  return d;
}

std::vector<DrawnVehicle> draw_truck_population(int count, std::uint64_t first_seed) {
  std::vector<DrawnVehicle> out;
  for (int i = 0; i < count; ++i) {
    out.push_back(draw_tractor(first_seed + static_cast<std::uint64_t>(i)));
  }
  return out;
}

}  // namespace vmass::sim

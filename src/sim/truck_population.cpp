#include "vmass/sim/truck_population.hpp"

namespace vmass::sim {

namespace {

constexpr double kG = 9.80665;

// The rigid truck's rear suspension reaches its bump stop near its own payload capacity; a
// tractor's carries the fifth-wheel load, so its stroke to the knee scales with the capacity.
void scale_rear_stroke(double capacity_ratio, TrueVehicle& v) {
  SuspensionParams& s = v.rear_right_suspension;
  const double empty_sprung_n = static_loads(v, v.empty).rear_right_n - s.unsprung_mass_kg * kG;
  const double z_empty = empty_sprung_n / s.stiffness_n_per_m;
  s.knee_compression_m = z_empty + (s.knee_compression_m - z_empty) * capacity_ratio;
}

}  // namespace

DrawnVehicle draw_tractor(std::uint64_t vehicle_seed) {
  DrawnVehicle d = draw_vehicle(VehicleClass::kHeavyTruck, vehicle_seed);
  d.id = std::string(kTractorIdPrefix) + "-" + std::to_string(vehicle_seed);
  d.tractor = true;
  const double rigid_capacity_kg = d.payload_capacity_kg;
  d.max_mass_kg = kTractorCombinationMaxKg;
  d.payload_capacity_kg = kTractorCombinationMaxKg - d.vehicle.empty.mass_kg;
  scale_rear_stroke(d.payload_capacity_kg / rigid_capacity_kg, d.vehicle);
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

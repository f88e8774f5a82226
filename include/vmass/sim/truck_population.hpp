// Truck population: tractors of the heavy-truck class that pull semi-trailers, drawn apart from
// the car population so that neither redraws the other (issue 29). A tractor is the
// heavy-truck class's vehicle of the same seed (its cab, chassis, powertrain, sensors, bus and
// knowledge), with the permitted mass of a tractor-trailer combination: 40 t, so its payload
// capacity is what the combination carries beyond the tractor's empty mass. Its id is
// "tractor-<seed>" (parse_vehicle_id knows it).
//
// The simulator carries a payload as point masses on the body, so a semi-trailer is modelled
// as its mass on the tractor's fifth wheel (0.80-0.95 of the wheelbase; the share on the
// trailer's own axles included): its inertia, rolling resistance and grade force are right, the
// tractor's axle loads are not.
//
// The development trucks start at seed kTruckFirstSeed, the held-out ones at
// kTruckHeldOutFirstSeed. Pure functions; thread-safe.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "vmass/sim/population.hpp"

namespace vmass::sim {

constexpr std::uint64_t kTruckFirstSeed = 200001;
constexpr std::uint64_t kTruckHeldOutFirstSeed = 300001;
constexpr double kTractorCombinationMaxKg = 40000.0;
constexpr const char* kTractorIdPrefix = "tractor";

/// The tractor of that seed.
DrawnVehicle draw_tractor(std::uint64_t vehicle_seed);
/// count tractors, seeds first_seed, first_seed + 1, ...
std::vector<DrawnVehicle> draw_truck_population(int count, std::uint64_t first_seed);

}  // namespace vmass::sim

// Lifetime: a vehicle of the population as it lives, drive after drive. Each drive is one of
// the population's everyday scenarios; it starts with the load the last drive left, changed
// while parked before at least half of the drives (a few passengers in or out, the boot filled
// or emptied, cargo loaded or unloaded), and it starts a day after the last one. The accuracy
// suite's lifetime mode (vmass-suite --lifetime) drives it through the daemon's state file,
// carried from drive to drive, beside the same drives replayed fresh.
//
// A tyre change (plan_lifetime's tyre_change_drive): worn tyres replaced by new ones while
// parked, the rolling radius 1-3 % larger from then on (tread of 2 mm against 8 mm), which
// the config's radius never hears of: the force a wheel torque makes and the wheels' speed
// signal both change by it (fit_tyres).
//
// A trailer change (plan_lifetime's trailer_change_drive; tractors only): the semi-trailer
// uncoupled while parked and another coupled, of another kind (a curtainsider, a tanker, a
// flatbed) and load. The simulator carries a trailer as its mass on the fifth wheel (see
// truck_population.hpp), so the other trailer is another such mass, and its drag area and
// rolling coefficient those of the combination times a drawn factor (couple_trailer): 0.75-1.3
// for the drag area (a flatbed's to a high box's) and 0.85-1.2 for the rolling coefficient (its
// tyres and axles). The config, written for the first trailer, is kept.
//
// Pure functions; thread-safe.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "vmass/sim/mass_properties.hpp"
#include "vmass/sim/population.hpp"

namespace vmass::sim {

/// A drive starts this long after the last one started (the drives' logs are a day apart).
constexpr double kLifetimeDriveSpacingS = 86400.0;

struct LifetimeDrive {
  int index = 1;  ///< 1-based
  std::string scenario;
  std::uint64_t seed = 1;         ///< the scenario's seed (its drive and noise)
  std::vector<LoadItem> payload;  ///< at the start, where it sits (placed by the realism)
  std::string load_change;        ///< what changed while parked before it; "" nothing
  double payload_change_kg = 0.0;
  /// The tyres' rolling radius against the vehicle's as drawn: 1 until a tyre change.
  double tyre_radius_factor = 1.0;
  /// The trailer's drag area and rolling coefficient against the combination's as drawn: 1
  /// until a trailer change.
  double trailer_drag_factor = 1.0;
  double trailer_rolling_factor = 1.0;
  std::string car_change;  ///< what changed on the car itself before it; "" nothing
};

/// The everyday scenarios a lifetime rotates through (no biased config, no bus faults, no
/// load deliberately at the bump stop).
std::vector<std::string> lifetime_scenario_names();

/// `drives` drives of `vehicle`'s life number `life` (>= 1; another life, other loads and
/// other drives). The load changes before every even drive, and before an odd one with
/// probability 0.3. With tyre_change_drive K > 1, new tyres are fitted before drive K (their
/// radius drawn apart from the loads: a life's loads and drives are the same with and
/// without). With trailer_change_drive L > 1 and a tractor, another trailer is coupled before
/// drive L: its load and factors drawn apart too, the drives before it the same with and
/// without.
std::vector<LifetimeDrive> plan_lifetime(const DrawnVehicle& vehicle, int drives,
                                         std::uint64_t life, int tyre_change_drive = 0,
                                         int trailer_change_drive = 0);

/// The combination with another trailer (LifetimeDrive's factors): its drag area and rolling
/// coefficients scaled.
void couple_trailer(double drag_factor, double rolling_factor, TrueVehicle* vehicle);

/// The vehicle on the tyres of factor `tyre_radius_factor` (LifetimeDrive): its rolling radius
/// scaled, and its speed signal, the wheels' turning times the radius the ESC assumes, scaled
/// by the inverse.
void fit_tyres(double tyre_radius_factor, TrueVehicle* vehicle);

/// The total mass of the items, kg.
double payload_mass_kg(const std::vector<LoadItem>& items);

}  // namespace vmass::sim

// vmass-replay --known-mass TIME:KG[:STD]: a mass the user declares for the load at TIME
// seconds after the log's first record (a weighbridge ticket, "empty, driver only"), as
// vmass-ctl declares it to a running vmassd. STD defaults to 0.5 % of KG.
#pragma once

#include <string>
#include <vector>

#include "vmass/core/vehicle_params.hpp"

namespace vmass {

struct KnownMassEvent {
  double time_s = 0.0;  ///< since the first record
  double mass_kg = 0.0;
  double std_kg = 0.0;
};

/// Parses the option's values, sorted by time; "" or why one is not TIME:KG[:STD] with a time
/// >= 0, a mass inside the vehicle's plausible band and a std > 0.
std::string parse_known_masses(const std::vector<std::string>& values, const VehicleParams& vehicle,
                               std::vector<KnownMassEvent>* out);

}  // namespace vmass

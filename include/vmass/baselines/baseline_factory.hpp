// The registry of baselines the accuracy suite scores next to vmass (issue 8):
//   paper       the paper's longitudinal block alone, as published        (paper_baseline.hpp)
//   paper_lp    the same block with a 1 Hz low-pass and NIG batches      (paper_lp_baseline.hpp)
//   vahidi2005  RLS with multiple forgetting on mass and grade           (vahidi2005_baseline.hpp)
//   fathy2008   RLS on supervisor-extracted high-frequency events        (fathy2008_baseline.hpp)
// Each with its default parameters. Thread-safe (no shared state).
#pragma once

#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "vmass/baselines/mass_baseline.hpp"
#include "vmass/baselines/nominal_vehicle.hpp"

namespace vmass::baselines {

/// The names make_baseline() knows, in the order above.
std::vector<std::string> baseline_names();

/// A baseline with its default parameters for a car and a tick rate; nullptr for an unknown name.
/// An invalid vehicle (NominalVehicle::validate) or tick rate gives a baseline that never reports
/// a mass.
std::unique_ptr<MassBaseline> make_baseline(std::string_view name, const NominalVehicle& vehicle,
                                            double tick_rate_hz);

}  // namespace vmass::baselines

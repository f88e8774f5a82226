// Every tick's estimate of a replay as columns, the estimate CSV's (docs/formats.md) in its
// order, for a pandas DataFrame or an Arrow table: numbers at full precision (the CSV rounds
// them), NaN in the belief cells before the first estimate (the CSV's empty cells), status and
// reason as codes into status_names() and reason_names().
// Not thread-safe; one per replay.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "vmass/core/estimate.hpp"

namespace vmass::python {

struct EstimateColumns {
  std::vector<double> time_s, mass_kg, mass_ci_low_kg, mass_ci_high_kg, mu_n;
  std::vector<std::uint8_t> status;
  std::vector<double> mass_std_kg;
  std::vector<std::uint8_t> reason;
  std::vector<std::int64_t> longitudinal_pairs, lateral_pairs;
  std::vector<double> longitudinal_availability, lateral_availability, initial_mass_kg;

  void add(const Estimate& e);
  std::size_t size() const { return time_s.size(); }
};

/// The names of EstimateStatus's and StatusReason's codes, as the CSV writes them.
std::vector<std::string> status_names();
std::vector<std::string> reason_names();

}  // namespace vmass::python

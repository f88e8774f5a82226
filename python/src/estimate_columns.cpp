#include "estimate_columns.hpp"

#include <limits>

namespace vmass::python {
namespace {

/// The names of codes 0, 1, ... of an enum, up to the first its name function does not know.
template <class Enum, class NameOf>
std::vector<std::string> names_of(NameOf name_of) {
  std::vector<std::string> names;
  for (int code = 0; code <= std::numeric_limits<std::uint8_t>::max(); ++code) {
    const std::string_view name = name_of(static_cast<Enum>(code));
    if (name == "unknown") break;
    names.emplace_back(name);
  }
  return names;
}

}  // namespace

void EstimateColumns::add(const Estimate& e) {
  // The CSV leaves the belief cells empty before the first estimate: a 0 would read as 0 kg.
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const bool mass = e.has_mass();
  time_s.push_back(to_seconds(e.time_us));
  mass_kg.push_back(mass ? e.mass_kg : nan);
  mass_ci_low_kg.push_back(mass ? e.ci_low_kg : nan);
  mass_ci_high_kg.push_back(mass ? e.ci_high_kg : nan);
  mu_n.push_back(mass ? e.mu_n : nan);
  status.push_back(static_cast<std::uint8_t>(e.status));
  mass_std_kg.push_back(mass ? e.mass_std_kg : nan);
  reason.push_back(static_cast<std::uint8_t>(e.reason));
  longitudinal_pairs.push_back(e.blocks[0].accepted);
  lateral_pairs.push_back(e.blocks[1].accepted);
  longitudinal_availability.push_back(e.blocks[0].availability());
  lateral_availability.push_back(e.blocks[1].availability());
  initial_mass_kg.push_back(mass ? e.initial_mass_kg : nan);
}

std::vector<std::string> status_names() { return names_of<EstimateStatus>(status_name); }
std::vector<std::string> reason_names() { return names_of<StatusReason>(reason_name); }

}  // namespace vmass::python

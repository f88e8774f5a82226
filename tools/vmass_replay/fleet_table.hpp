// The summary table of many logs (vmass-replay --logs), one row per log, as CSV or as JSON
// lines with the same keys:
//   log, frames, corrupt_lines, duration_s, ticks, estimator, status, reason, mass_kg,
//   mass_ci_low_kg, mass_ci_high_kg, mass_std_kg, mu_n, initial_mass_kg, prior, pairs_used,
//   pairs_accepted, longitudinal_availability, lateral_availability, reinitialisations, error
// The estimate is the final one (the open Bayes batch flushed), as --log's summary reports it.
// A log without an estimate has empty cells (JSON null) for the masses; a log that could not
// be replayed has only its path and the error. Numbers at the estimate CSV's precisions, written
// with std::to_chars (vmass/csv/fixed_decimal.hpp; the JSON's read back as the same values,
// vmass/json/json.hpp); a CSV cell holding a comma or a quote is quoted (RFC 4180).
// Thread-safe (pure functions).
#pragma once

#include <string>

#include "fleet_replay.hpp"

namespace vmass {

std::string fleet_csv_header();
/// One row, with its newline.
std::string fleet_csv_row(const FleetLogResult& r);
/// One JSON object, with its newline.
std::string fleet_json_line(const FleetLogResult& r);

}  // namespace vmass

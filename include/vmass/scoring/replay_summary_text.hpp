// What vmass-replay prints of a ReplaySummary: the human table, or one JSON object with the
// same facts (docs/formats.md, "Replay summary"). Thread-safe (pure functions).
#pragma once

#include <string>
#include <string_view>

#include "vmass/scoring/replay_summary.hpp"

namespace vmass::scoring {

/// The human table vmass-replay prints.
std::string replay_table(const ReplaySummary::Result& r, const std::string& estimator_name);
/// One JSON object with everything the table shows (for the scenario suite).
std::string replay_json(const ReplaySummary::Result& r, const std::string& estimator_name);

/// How a prior is described to a reader, e.g. "static, eq. 3" or "no standstill before
/// driving: the empty mass".
std::string_view describe_prior(StatusReason prior_reason);

}  // namespace vmass::scoring

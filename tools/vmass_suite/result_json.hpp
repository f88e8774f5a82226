// The JSON fields of one estimator's result on one drive (the suite's JSON lines, read by
// accuracy_report.py): the knowledge, the estimator, whether supported, and its scores.
#pragma once

#include <nlohmann/json.hpp>

#include "suite_run.hpp"

namespace vmass::suite {

void add_result_fields(const EstimatorResult& r, nlohmann::json* j);

}  // namespace vmass::suite

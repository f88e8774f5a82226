// One tick's estimate against the truth at that tick: the signed error in percent, and whether
// the interval covers the truth. Both scorers (replay_summary.hpp, accuracy_metrics.hpp) use
// these, so that an error or a coverage means the same in every report. Thread-safe.
#pragma once

namespace vmass::scoring {

/// (estimate - truth) / truth, in percent.
constexpr double error_pct(double estimate_kg, double truth_kg) {
  return 100.0 * (estimate_kg - truth_kg) / truth_kg;
}

/// Whether [low, high] contains the truth, both bounds included.
constexpr bool interval_covers(double low_kg, double high_kg, double truth_kg) {
  return low_kg <= truth_kg && truth_kg <= high_kg;
}

}  // namespace vmass::scoring

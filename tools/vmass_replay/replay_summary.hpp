// ReplaySummary: what vmass-replay reports about a run, and how good it was against a truth
// (vmass/csv/truth_csv.hpp).
//
// Metrics (per run): final mass and error; time until the estimate stays within 5%, 2% and 1%
// of the truth until the end (only when the final estimate used a pair: a prior that happens to
// be close is no result); interval coverage (fraction of ticks with a dynamic estimate whose
// 95% interval contains the truth); the prior and where it came from; pairs used in the
// estimate and accepted by the supervisor, apart (Bayes holds a batch back until it completes
// or is flushed); availability per block; status at the end.
// Not thread-safe.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "vmass/core/estimate.hpp"
#include "vmass/csv/truth_csv.hpp"

namespace vmass {

class ReplaySummary {
 public:
  explicit ReplaySummary(std::optional<Truth> truth) : truth_(std::move(truth)) {}

  /// The estimate of each tick, in order.
  void add(const Estimate& estimate);
  /// The estimate after Pipeline::flush() at the end of the input (same time as the last tick,
  /// the open Bayes batch taken in): it becomes the final estimate; no tick is counted.
  void finish(const Estimate& flushed);

  struct Result {
    bool has_estimate = false;
    Estimate final_estimate;
    long pairs_accepted = 0;  ///< by the supervisor, both blocks (pairs_used: in the estimate)
    std::optional<double> true_mass_kg;
    std::optional<double> error_percent;  ///< (estimate - truth) / truth
    /// Time from which the estimate stays within 5/2/1 % of the truth to the end; empty when
    /// it never does, and when the final estimate used no pair (a prior proves nothing).
    std::optional<double> time_within_5_s, time_within_2_s, time_within_1_s;
    std::optional<double> coverage;  ///< fraction of dynamic ticks covering the truth
    double duration_s = 0.0;
    long ticks = 0;
    long reinitialisations = 0;
  };
  Result result() const;
  /// The human table vmass-replay prints.
  std::string table(const std::string& estimator_name) const;
  /// One JSON object with everything the table shows (for the scenario suite).
  std::string json(const std::string& estimator_name) const;

 private:
  void check_tolerances(const Estimate& e);

  std::optional<Truth> truth_;
  TimeUs first_us_ = 0;
  bool started_ = false;
  Estimate last_;
  bool has_last_ = false;
  long ticks_ = 0;
  long reinitialisations_ = 0;
  long dynamic_ticks_ = 0;
  long covered_ticks_ = 0;
  // Last time each tolerance was violated (the estimate stays within after that).
  std::optional<TimeUs> last_outside_[3];
  bool any_mass_ = false;
  TimeUs first_mass_us_ = 0;
};

/// How a prior is described to a reader, e.g. "static, eq. 3" or "no standstill before
/// driving: the empty mass".
std::string_view describe_prior(StatusReason prior_reason);

}  // namespace vmass

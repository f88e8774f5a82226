// Truth and ReplaySummary: how good a run was against the simulator's truth.
//
// Metrics (per run): final mass and error; time until the estimate stays within 5%, 2% and 1%
// of the truth until the end; interval coverage (fraction of ticks with a dynamic estimate whose
// 95% interval contains the truth); availability per block; status at the end.
// Not thread-safe.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "vmass/core/estimate.hpp"

namespace vmass {

/// The true mass over time (truth.csv: time_s, mass_kg, ...).
class Truth {
 public:
  /// Empty error on success.
  static std::optional<Truth> load(const std::string& path, std::string* error);
  Truth() = default;
  Truth(std::vector<TimeUs> times, std::vector<double> masses);
  /// The true mass at time t (the last row at or before t).
  double mass_at(TimeUs t) const;
  bool empty() const { return times_.empty(); }

 private:
  std::vector<TimeUs> times_;
  std::vector<double> masses_kg_;
};

class ReplaySummary {
 public:
  explicit ReplaySummary(std::optional<Truth> truth) : truth_(std::move(truth)) {}

  void add(const Estimate& estimate);

  struct Result {
    bool has_estimate = false;
    Estimate final_estimate;
    std::optional<double> true_mass_kg;
    std::optional<double> error_percent;       ///< (estimate - truth) / truth
    std::optional<double> time_within_5_s, time_within_2_s, time_within_1_s;  ///< empty: never
    std::optional<double> coverage;            ///< fraction of dynamic ticks covering the truth
    double duration_s = 0.0;
    long ticks = 0;
    long reinitialisations = 0;
  };
  Result result() const;
  /// The human table vmass-replay prints.
  std::string table(const std::string& estimator_name) const;
  /// One JSON object with the same numbers (for the scenario suite).
  std::string json(const std::string& estimator_name) const;

 private:
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

}  // namespace vmass

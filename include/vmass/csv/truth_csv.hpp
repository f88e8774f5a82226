// Truth: the true mass over time, from a truth.csv (docs/formats.md: time_s, mass_kg, then any
// other columns), and the rule that says whether a truth describes a replay's time base.
// Not thread-safe.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "vmass/core/time.hpp"

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
  TimeUs first_time_us() const { return times_.front(); }
  TimeUs last_time_us() const { return times_.back(); }

  /// The time-base rule: a truth describes a replay when the replay's first tick lies within
  /// the truth's time span (first to last row), give or take one tick period. vmass-sim writes
  /// its log, samples and truth from 0 s, so they line up; a log recorded on a car carries epoch
  /// times, and a truth starting at 0 s does not describe it. "" when the rule holds, else why
  /// not (both spans, in seconds).
  std::string check_time_base(TimeUs first_tick_us, TimeUs tick_period_us) const;

 private:
  std::vector<TimeUs> times_;
  std::vector<double> masses_kg_;
};

}  // namespace vmass

// Truth: what a run is scored against, the true mass (and, when known, the true speed) over
// time. vmass-replay reads one from a truth.csv (truth_csv.hpp); the accuracy suite takes the
// simulator's rows (its speed gives the drive's start). Not thread-safe.
#pragma once

#include <string>
#include <vector>

#include "vmass/core/time.hpp"

namespace vmass::scoring {

class Truth {
 public:
  Truth() = default;
  /// Rows in increasing time; speeds empty when not known (the drive then starts at once).
  Truth(std::vector<TimeUs> times, std::vector<double> masses_kg,
        std::vector<double> speeds_mps = {});

  /// The true mass at t: the last row at or before t, the first row before it; NaN when empty.
  double mass_at(TimeUs t) const;
  /// The first time the true speed exceeds 0.5 m/s (the first row's time if never; 0 if empty).
  TimeUs drive_start_us() const;
  bool empty() const { return times_.empty(); }
  std::size_t size() const { return times_.size(); }
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
  std::vector<double> speeds_mps_;
};

}  // namespace vmass::scoring

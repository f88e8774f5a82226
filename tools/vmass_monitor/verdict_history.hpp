// Why the longitudinal block has taken no pair lately, for vmass-monitor: vmassd's status counts
// the ticks of each pair verdict since it started (status_t.longitudinal_verdict_ticks, index 0
// "accepted"); the monitor keeps those counts from the statuses of the last minutes and, when
// the accepted count has not moved for a while, says which verdicts the ticks of that stretch
// had instead ("no longitudinal pair in 180 s: 17,800 ticks small_delta_force, 200 settling").
//
// The stretch is measured in vmassd's ticks (ticks / tick_rate_hz: the drive's time, also on a
// replay at any speed); the history is kept by the monitor's own clock. Pure: times are seconds
// on any monotonic clock, given by the caller; not thread-safe.
#pragma once

#include <cstdint>
#include <deque>
#include <string>
#include <utility>
#include <vector>

#include <vmass/status_t.hpp>

namespace vmass::monitor {

/// The latest stretch without an accepted longitudinal pair.
struct NoPairStretch {
  double span_s = 0.0;  ///< its length, s of ticks; 0: nothing to report
  /// The ticks of each other verdict over it, most first (none with 0 ticks).
  std::vector<std::pair<std::string, std::int64_t>> verdict_ticks;
};

class VerdictHistory {
 public:
  /// Statuses are kept for `keep_s` seconds (of the caller's clock); a stretch is reported once
  /// it is `shortest_s` seconds of ticks long.
  explicit VerdictHistory(double keep_s = 180.0, double shortest_s = 30.0)
      : keep_s_(keep_s), shortest_s_(shortest_s) {}

  /// A status received at `t_s` (times never decrease). One without verdicts is ignored; one of
  /// a restarted vmassd (fewer ticks, other verdict names) starts the history again.
  void add(double t_s, const vmass::status_t& status);

  /// The stretch since the last status whose accepted count moved (or since the oldest kept).
  NoPairStretch no_pair() const;

 private:
  struct Snapshot {
    double t_s = 0.0;
    std::int64_t ticks = 0;
    double tick_rate_hz = 0.0;
    std::vector<std::int64_t> counts;  ///< longitudinal_verdict_ticks
  };
  double keep_s_, shortest_s_;
  std::vector<std::string> names_;
  std::deque<Snapshot> snapshots_;
};

}  // namespace vmass::monitor

// What vmass-monitor says about how alive vmassd is: each channel's message rate over the last
// few seconds (not since the monitor started: a daemon that stopped shows as stopped), how long
// a channel has been silent, and when that silence means the daemon is gone.
//
// Pure: times are seconds on any monotonic clock, given by the caller; not thread-safe.
#pragma once

#include <deque>

namespace vmass::monitor {

/// Three status periods, or three of the estimates' own mean intervals (a decimated estimate),
/// or 3 s, whichever is longest: no estimate for that long and vmassd is taken for gone.
double silence_limit_s(double status_period_s, double mean_estimate_interval_s);

/// The window the rates are measured over: 5 s, or three status periods when that is longer.
double rate_window_s(double status_period_s);

/// One channel's arrivals over a sliding window.
class RecentRate {
 public:
  explicit RecentRate(double window_s) : window_s_(window_s) {}

  /// One message at `t_s` (times never decrease).
  void add(double t_s);

  /// Messages per second over the window ending at `now_s`: the mean interval of the
  /// messages in it, but never more than their number over the time since the first of them,
  /// so that the rate falls while nothing arrives and is 0 once the window is empty. 0 with
  /// fewer than two messages in the window.
  double rate_hz(double now_s);

  /// Seconds since the last message; negative before the first.
  double silent_s(double now_s) const { return count_ == 0 ? -1.0 : now_s - last_; }

  /// Messages since the start.
  long count() const { return count_; }

  /// Mean interval since the first message (0 with fewer than two).
  double mean_interval_s() const;

 private:
  double window_s_;
  std::deque<double> times_;  ///< the arrivals within the window
  long count_ = 0;
  double first_ = 0.0, last_ = 0.0;
};

}  // namespace vmass::monitor

// TickContinuity: tells whether a tick follows the previous one by exactly one tick period
// (within half a period). Filters and differences assume uniform sampling, so a baseline restarts
// its pipeline at any tick that does not (a hole in the data, a repeated or out-of-order stamp).
// Not thread-safe; no allocation.
#pragma once

#include "vmass/core/time.hpp"

namespace vmass::baselines {

class TickContinuity {
 public:
  /// tick_rate_hz > 0.
  explicit TickContinuity(double tick_rate_hz);

  /// Record the tick at time_us; true when it is one period after the previous recorded tick
  /// (false for the first tick).
  bool follows(vmass::TimeUs time_us);
  void clear() { has_last_ = false; }

 private:
  vmass::TimeUs period_us_;
  vmass::TimeUs tolerance_us_;
  vmass::TimeUs last_us_ = 0;
  bool has_last_ = false;
};

}  // namespace vmass::baselines

// TickGrid: the instant tick k describes. One rule for every front end (vmass-replay,
// vmass-calibrate --ballast LOG, vmassd live and replayed):
//
//   T_k = T_0 + round(k * 1e6 / tick_rate_hz)  microseconds
//
// T_0 is the first record's time for a recording (log time), CLOCK_REALTIME at tick 0 for a
// live bus. Tick k sees every record stamped at or before T_k (TickDriver applies them).
// Rounding each T_k from k, rather than adding a rounded period, keeps the grid exact over any
// run length at rates whose period is not a whole number of microseconds.
//
// Plain values; thread-safe to share read-only.
#pragma once

#include <cmath>
#include <cstdint>

#include "vmass/core/time.hpp"

namespace vmass::runtime {

class TickGrid {
 public:
  /// tick_rate_hz > 0.
  TickGrid(TimeUs t0_us, double tick_rate_hz) : t0_us_(t0_us), tick_rate_hz_(tick_rate_hz) {}

  TimeUs time_of(std::int64_t k) const {
    return t0_us_ + static_cast<TimeUs>(std::llround(static_cast<double>(k) * 1e6 / tick_rate_hz_));
  }
  TimeUs t0_us() const { return t0_us_; }
  double tick_rate_hz() const { return tick_rate_hz_; }

 private:
  TimeUs t0_us_;
  double tick_rate_hz_;
};

}  // namespace vmass::runtime

// Time in vmass: integer microseconds, the LCM `utime` convention.
//
// The estimation core never reads a clock: every Sample carries the time it describes, and the
// core derives intervals from those stamps. Callers own the clock (the daemon: CLOCK_MONOTONIC
// or the log's timestamps; replay: the log).
#pragma once

#include <cstdint>

namespace vmass {

/// A point in time or a duration, in microseconds.
using TimeUs = std::int64_t;

constexpr TimeUs kUsPerSecond = 1'000'000;

constexpr double to_seconds(TimeUs t) { return static_cast<double>(t) * 1e-6; }

/// Nearest microsecond of a time in seconds.
constexpr TimeUs from_seconds(double s) {
  return static_cast<TimeUs>(s * 1e6 + (s >= 0.0 ? 0.5 : -0.5));
}

}  // namespace vmass

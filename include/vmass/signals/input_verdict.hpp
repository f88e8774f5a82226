// InputVerdict: why an estimator input is invalid at a tick, as data (the estimator thread
// records it without allocating; the status publisher turns it into text).
//
//   fault             value          bound
//   kNotReceived      -              -
//   kStale            age, s         timeout, s
//   kMessageInvalid   DBC message    -            (its E2E checks failed; `message` says which)
//   kInvalidValue     -              -            (NaN/inf, or outside an enforced DBC range)
//   kBelowMinimum     value (SI)     minimum      (the input kind's physical limits)
//   kAboveMaximum     value (SI)     maximum
//   kRateOfChange     |rate|, SI/s   max rate
//   kStuck            frozen for, s  stuck_s      (while its witness input moved)
//   kSpeedVsAccelX    residual, m/s  tolerance    (delta speed against the integrated accel_x)
//   kSpeedAccelScale  fitted k       tolerance    (delta speed = k x integrated accel_x: units)
//   kYawVsAccelY      residual rad/s tolerance    (yaw rate against accel_y / speed, steady turn)
//
// Plain value; thread-safe to copy.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

namespace vmass::signals {

/// "Never" for a time: the most negative microsecond, so that every time a recording can hold,
/// before 1970 too (a log's times are negative then), is a real time. Compare with ==, and never
/// subtract it from a time.
inline constexpr std::int64_t kNeverUs = INT64_MIN;

enum class InputFault : std::uint8_t {
  kNone = 0,
  kNotReceived,
  kStale,
  kMessageInvalid,
  kInvalidValue,
  kBelowMinimum,
  kAboveMaximum,
  kRateOfChange,
  kStuck,
  kSpeedVsAccelX,
  kSpeedAccelScale,
  kYawVsAccelY,
};

/// Stable snake_case name ("rate_of_change").
std::string_view input_fault_name(InputFault fault);

struct InputVerdict {
  InputFault fault = InputFault::kNone;
  double value = 0.0;
  double bound = 0.0;
  int message = -1;  ///< kMessageInvalid: the DBC message's index
};

/// "rate_of_change: 1780 > 50 per s", "message_invalid: ESC_Speed", "" for kNone.
/// `message_name` names verdict.message (may be empty).
std::string describe(const InputVerdict& verdict, std::string_view message_name = {});

}  // namespace vmass::signals

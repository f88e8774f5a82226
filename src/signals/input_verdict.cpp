#include "vmass/signals/input_verdict.hpp"

#include <cstdio>

namespace vmass::signals {

std::string_view input_fault_name(InputFault fault) {
  switch (fault) {
    case InputFault::kNone:
      return "none";
    case InputFault::kNotReceived:
      return "not_received";
    case InputFault::kStale:
      return "stale";
    case InputFault::kMessageInvalid:
      return "message_invalid";
    case InputFault::kInvalidValue:
      return "invalid_value";
    case InputFault::kBelowMinimum:
      return "below_minimum";
    case InputFault::kAboveMaximum:
      return "above_maximum";
    case InputFault::kRateOfChange:
      return "rate_of_change";
    case InputFault::kStuck:
      return "stuck";
    case InputFault::kSpeedVsAccelX:
      return "speed_vs_accel_x";
    case InputFault::kSpeedAccelScale:
      return "speed_accel_scale";
    case InputFault::kYawVsAccelY:
      return "yaw_rate_vs_accel_y";
  }
  return "unknown";
}

std::string describe(const InputVerdict& v, std::string_view message_name) {
  std::string text(input_fault_name(v.fault));
  char buf[96] = "";
  switch (v.fault) {
    case InputFault::kNone:
      return "";
    case InputFault::kNotReceived:
    case InputFault::kInvalidValue:
      return text;
    case InputFault::kMessageInvalid:
      return text + ": " + (message_name.empty() ? std::string("?") : std::string(message_name));
    case InputFault::kStale:
      std::snprintf(buf, sizeof buf, ": %.3g s old > %.3g s", v.value, v.bound);
      break;
    case InputFault::kBelowMinimum:
      std::snprintf(buf, sizeof buf, ": %.6g < %.6g", v.value, v.bound);
      break;
    case InputFault::kAboveMaximum:
      std::snprintf(buf, sizeof buf, ": %.6g > %.6g", v.value, v.bound);
      break;
    case InputFault::kRateOfChange:
      std::snprintf(buf, sizeof buf, ": %.4g > %.4g per s", v.value, v.bound);
      break;
    case InputFault::kStuck:
      std::snprintf(buf, sizeof buf, ": unchanged for %.3g s (>= %.3g s) while its witness moved",
                    v.value, v.bound);
      break;
    case InputFault::kSpeedVsAccelX:
      std::snprintf(buf, sizeof buf, ": residual %.3g m/s, tolerance %.3g m/s", v.value, v.bound);
      break;
    case InputFault::kYawVsAccelY:
      std::snprintf(buf, sizeof buf, ": residual %.3g rad/s, tolerance %.3g rad/s", v.value,
                    v.bound);
      break;
    case InputFault::kSpeedAccelScale:
      std::snprintf(buf, sizeof buf,
                    ": delta speed = %.3g x integrated accel_x (tolerance %.3g): a unit wrong?",
                    v.value, v.bound);
      break;
  }
  return text + buf;
}

}  // namespace vmass::signals

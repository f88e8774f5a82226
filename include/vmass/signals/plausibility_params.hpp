// PlausibilityParams: what a believable raw input is, per input kind, and the config's
// `can.plausibility` section that overrides it. DBC [min|max] ranges are not validity (real
// files carry wrong ones); these limits are. All values SI (the input's unit: m/s, m/s^2, rad,
// rad/s, Pa, N m, m).
//
//   can:
//     plausibility:
//       enabled: true
//       inputs:                      # per input; omitted keys keep their defaults (below)
//         speed: {min: -15, max: 120, max_rate_per_s: 50, stuck_s: 0, stuck_band: 0}
//       speed_vs_accel_x: {enabled: true, window_s: 1.0, tolerance_mps: 1.0,
//                          tolerance_fraction: 0.2, smoothing_s: 5.0, scale_tolerance: 0.3,
//                          scale_time_s: 60}
//       yaw_rate_vs_accel_y: {enabled: true, window_s: 1.0, min_speed_mps: 5.0,
//                             min_accel_y_mps2: 1.0, steady_accel_y_mps2: 0.5,
//                             steady_yaw_rate_radps: 0.05, tolerance_radps: 0.05,
//                             tolerance_fraction: 0.25}
//
// Defaults (min, max, max_rate_per_s, stuck_s, stuck_band; 0 = check off, band 0: bit for bit):
//   wheel_torque          -3e5, 3e5 N m     -        -     -
//   brake_pressure        -2e5, 3e7 Pa      -        -     -
//   accel_x               -30, 30 m/s^2     -        -     -   (frozen: speed_vs_accel_x)
//   accel_y               -30, 30 m/s^2     -        5 s   0.05 m/s^2
//   yaw_rate              -5, 5 rad/s       30/s     5 s   0.01 rad/s
//   speed                 -15, 120 m/s      50/s     -     -
//   steering_wheel_angle  -20, 20 rad       40/s     5 s   0.035 rad (2 deg)
//   rear_right_deflection -0.5, 0.5 m       5/s      -     -
//   gear                  -5, 30            -        -     -
// A stuck check counts only while the input's witness moves (see input_plausibility.hpp); an
// input without a witness is stuck when it repeats one value for stuck_s while frames come.
//
// Configuration time only; plain values.
#pragma once

#include <array>
#include <string>

#include <yaml-cpp/yaml.h>

#include "vmass/core/sample.hpp"

namespace vmass::signals {

struct InputLimits {
  double min = -1e300;
  double max = 1e300;
  double max_rate_per_s = 0.0;  ///< 0: not checked
  double stuck_s = 0.0;         ///< 0: not checked
  double stuck_band = 0.0;      ///< a value within this of where it stood has not moved
};

struct SpeedAccelCheck {
  bool enabled = true;
  double window_s = 1.0;
  double tolerance_mps = 1.0;
  double tolerance_fraction = 0.2;  ///< of |integral of accel_x| over the window
  double smoothing_s = 5.0;         ///< time constant of the slow part (grade, bias) removed
  double scale_tolerance = 0.3;     ///< |k - 1| allowed for delta v = k * integral; 0: off
  double scale_time_s = 60.0;       ///< memory of that fit
};

struct YawAccelCheck {
  bool enabled = true;
  double window_s = 1.0;
  double min_speed_mps = 5.0;
  double min_accel_y_mps2 = 1.0;
  double steady_accel_y_mps2 = 0.5;     ///< largest spread of accel_y in a steady window
  double steady_yaw_rate_radps = 0.05;  ///< largest spread of yaw_rate in a steady window
  double tolerance_radps = 0.05;
  double tolerance_fraction = 0.25;  ///< of |yaw rate|
};

struct PlausibilityParams {
  bool enabled = true;
  std::array<InputLimits, kInputCount> inputs = default_input_limits();
  SpeedAccelCheck speed_vs_accel_x;
  YawAccelCheck yaw_rate_vs_accel_y;

  static std::array<InputLimits, kInputCount> default_input_limits();
};

/// Parses `can.plausibility` (null: the defaults). "" and *out, or "file:line: key: message".
std::string parse_plausibility(const YAML::Node& node, const std::string& file,
                               PlausibilityParams* out);

}  // namespace vmass::signals

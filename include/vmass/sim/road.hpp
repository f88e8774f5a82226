// Road: the surface under the simulated car as functions of the distance travelled s (the car's
// path in the plane is whatever its steering makes; the road is "unrolled" along it).
//
//   grade theta(s): positive uphill in the direction of travel, rad
//   bank  phi(s):   positive when the left side is higher, rad
//
// Gravity in the body frame is g_b = (-g sin theta, -g cos theta sin phi, -g cos theta cos phi);
// an accelerometer measures the specific force a - g_b, so a_x,meas = dv_x/dt - r v_y + g sin theta
// and a_y,meas = dv_y/dt + r v_x + g cos theta sin phi.
//
// With the road_roughness effect: roughness(s) scales the vibration the IMU sees (0 smooth,
// about 1 for a worn road, 3 for a bad one), and each speed bump at s_b gives each axle, as it
// crosses [s_b, s_b + bump_length_m], a half-sine longitudinal deceleration pulse of peak
// severity * min(1, v / 8 m/s) (the horizontal part of the contact force on the bump's flank).
// friction(s) is the tyre-road friction coefficient the ABS limits braking to (abs_esc).
// Value type; thread-safe to read.
#pragma once

#include <string>
#include <vector>

#include "vmass/sim/piecewise_linear.hpp"

namespace vmass::sim {

struct SpeedBump {
  double position_m = 0.0;
  double severity_mps2 = 2.0;
};

struct Road {
  PiecewiseLinear grade_rad{0.0};  ///< over distance, m
  PiecewiseLinear bank_rad{0.0};   ///< over distance, m
  PiecewiseLinear roughness{0.0};  ///< over distance, m (road_roughness)
  PiecewiseLinear friction{1.0};   ///< over distance, m (abs_esc)
  std::vector<SpeedBump> bumps;    ///< in increasing position (road_roughness)
  double bump_length_m = 0.4;

  double grade_at(double distance_m) const { return grade_rad(distance_m); }
  double bank_at(double distance_m) const { return bank_rad(distance_m); }
  /// The bump pulse (m/s^2, >= 0) on an axle at distance_m moving at speed_mps.
  double bump_deceleration_mps2(double axle_distance_m, double speed_mps) const;

  std::string validate() const;
};

/// Grade in rad from a slope in percent (rise over run).
double grade_from_percent(double percent);

}  // namespace vmass::sim

// Road: the surface under the simulated car as functions of the distance travelled s (the car's
// path in the plane is whatever its steering makes; the road is "unrolled" along it).
//
//   grade theta(s): positive uphill in the direction of travel, rad
//   bank  phi(s):   positive when the left side is higher, rad
//
// Gravity in the body frame is g_b = (-g sin theta, -g cos theta sin phi, -g cos theta cos phi);
// an accelerometer measures the specific force a - g_b, so a_x,meas = dv_x/dt - r v_y + g sin theta
// and a_y,meas = dv_y/dt + r v_x + g cos theta sin phi. Value type; thread-safe to read.
#pragma once

#include <string>

#include "vmass/sim/piecewise_linear.hpp"

namespace vmass::sim {

struct Road {
  PiecewiseLinear grade_rad{0.0};  ///< over distance, m
  PiecewiseLinear bank_rad{0.0};   ///< over distance, m

  double grade_at(double distance_m) const { return grade_rad(distance_m); }
  double bank_at(double distance_m) const { return bank_rad(distance_m); }

  std::string validate() const;
};

/// Grade in rad from a slope in percent (rise over run).
double grade_from_percent(double percent);

}  // namespace vmass::sim

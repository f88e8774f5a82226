// Lateral tyre forces of the linear single-track model (paper eqs. 10 and 12), in ISO 8855.
//
// Sign convention (fixed here once, proven by tests/core/lateral_forces_test.cpp with a steady
// turn whose answer is known): x forward, y left, yaw rate r positive turning left, road-wheel
// angle delta_f positive steering left, slip angles positive when they produce a force to the
// left:
//   alpha_f = delta_f - atan(v_y / v_x) - l_f r / v_x
//   alpha_r =         - atan(v_y / v_x) + l_r r / v_x
//   F_yf = C_alpha_f alpha_f,   F_yr = C_alpha_r alpha_r                             eq. (10)
//   F_lat = F_yf cos(delta_f) + F_yr           so that  M a_y = F_lat  in a steady turn (8)
// The paper's eq. (12) prints both slip angles with the opposite sign (force to the right); with
// its eq. (10) and (8) that would give M a_y = -F_lat, so we flip it.
#pragma once

#include "vmass/core/vehicle_params.hpp"

namespace vmass {

struct AxleLateralForces {
  double slip_front_rad = 0.0;
  double slip_rear_rad = 0.0;
  double front_n = 0.0;
  double rear_n = 0.0;
  double total_n = 0.0;  ///< F_yf cos(delta_f) + F_yr
};

/// Requires |v_x| > 0.
AxleLateralForces axle_lateral_forces(const VehicleParams& vehicle, double speed_mps,
                                      double lateral_velocity_mps, double yaw_rate_radps,
                                      double road_wheel_angle_rad);

}  // namespace vmass

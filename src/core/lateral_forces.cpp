#include "vmass/core/lateral_forces.hpp"

#include <cmath>

namespace vmass {

AxleLateralForces axle_lateral_forces(const VehicleParams& vehicle, double speed_mps,
                                      double lateral_velocity_mps, double yaw_rate_radps,
                                      double road_wheel_angle_rad) {
  AxleLateralForces f;
  const double body_slip = std::atan(lateral_velocity_mps / speed_mps);
  f.slip_front_rad =
      road_wheel_angle_rad - body_slip - vehicle.cg_to_front_axle_m * yaw_rate_radps / speed_mps;
  f.slip_rear_rad = -body_slip + vehicle.cg_to_rear_axle_m() * yaw_rate_radps / speed_mps;
  f.front_n = vehicle.cornering_stiffness_front_n_per_rad * f.slip_front_rad;
  f.rear_n = vehicle.cornering_stiffness_rear_n_per_rad * f.slip_rear_rad;
  f.total_n = f.front_n * std::cos(road_wheel_angle_rad) + f.rear_n;
  return f;
}

}  // namespace vmass

#include "vmass/sim/true_vehicle.hpp"

#include <algorithm>
#include <cmath>

namespace vmass::sim {

std::string TrueVehicle::validate() const {
  if (auto m = empty.validate("vehicle.empty."); !m.empty()) return m;
  if (!(wheelbase_m > 0.5)) return "vehicle.wheelbase_m must be > 0.5";
  if (!(empty.cg_x_m > 0.0 && empty.cg_x_m < wheelbase_m)) {
    return "vehicle.empty.cg_x_m must be in (0, wheelbase_m)";
  }
  if (!(track_m > 0.5)) return "vehicle.track_m must be > 0.5";
  if (!(wheel_radius_m > 0.1)) return "vehicle.wheel_radius_m must be > 0.1";
  if (!(steering_ratio > 1.0)) return "vehicle.steering_ratio must be > 1";
  if (!(brake_gain_n_per_pa > 0.0)) return "vehicle.brake_gain_n_per_pa must be > 0";
  if (!(brake_front_share >= 0.0 && brake_front_share <= 1.0)) {
    return "vehicle.brake_front_share must be in [0, 1]";
  }
  if (!(drag_area_m2 >= 0.0)) return "vehicle.drag_area_m2 must be >= 0";
  if (!(air_density_kg_per_m3 >= 0.0)) return "vehicle.air_density_kg_per_m3 must be >= 0";
  if (!(rolling_resistance_coeff >= 0.0 && rolling_resistance_coeff < 0.1)) {
    return "vehicle.rolling_resistance_coeff must be in [0, 0.1)";
  }
  if (!(gravity_mps2 > 9.7 && gravity_mps2 < 9.9))
    return "vehicle.gravity_mps2 must be in (9.7, 9.9)";
  if (!(roll_stiffness_front_share >= 0.0 && roll_stiffness_front_share <= 1.0)) {
    return "vehicle.roll_stiffness_front_share must be in [0, 1]";
  }
  if (!(load_transfer_time_constant_s > 0.0)) {
    return "vehicle.load_transfer_time_constant_s must be > 0";
  }
  if (auto m = front_tyre.validate("vehicle.front_tyre."); !m.empty()) return m;
  if (auto m = rear_tyre.validate("vehicle.rear_tyre."); !m.empty()) return m;
  if (auto m = powertrain.validate("vehicle.powertrain."); !m.empty()) return m;
  if (auto m = rear_right_suspension.validate("vehicle.rear_right_suspension."); !m.empty())
    return m;
  if (auto m = driveline.validate("vehicle.driveline."); !m.empty()) return m;
  if (auto m = imu.validate("vehicle.imu."); !m.empty()) return m;
  if (auto m = brakes.validate("vehicle.brakes."); !m.empty()) return m;
  if (auto m = wheel_speed.validate("vehicle.wheel_speed."); !m.empty()) return m;
  if (!(rolling_resistance_speed_coeff_s2_per_m2 >= 0.0 && driveline_viscous_n_per_mps >= 0.0 &&
        side_force_area_m2 >= 0.0)) {
    return "vehicle: speed-dependent resistances and side force area must be >= 0";
  }
  if (!(levelling_time_constant_s > 0.0)) return "vehicle.levelling_time_constant_s must be > 0";
  return "";
}

double front_drive_share(DrivenAxle a) {
  if (a == DrivenAxle::kFront) return 1.0;
  return a == DrivenAxle::kRear ? 0.0 : 0.5;
}

std::string_view driven_axle_name(DrivenAxle a) {
  switch (a) {
    case DrivenAxle::kFront:
      return "front";
    case DrivenAxle::kRear:
      return "rear";
    case DrivenAxle::kAll:
      return "all";
  }
  return "unknown";
}

std::string BrakeParams::validate(const std::string& prefix) const {
  if (!std::isfinite(pressure_offset_pa)) return prefix + "pressure_offset_pa must be finite";
  if (!(heat_capacity_j_per_k > 0.0 && cooling_time_s > 0.0)) {
    return prefix + "heat_capacity_j_per_k and cooling_time_s must be > 0";
  }
  if (!(fade_full_c > fade_start_c)) return prefix + "fade_full_c must be > fade_start_c";
  if (!(fade_max_fraction >= 0.0 && fade_max_fraction < 1.0)) {
    return prefix + "fade_max_fraction must be in [0, 1)";
  }
  return "";
}

double BrakeParams::gain_scale(double temperature_c) const {
  const double x = (temperature_c - fade_start_c) / (fade_full_c - fade_start_c);
  return 1.0 - fade_max_fraction * std::clamp(x, 0.0, 1.0);
}

std::string WheelSpeedParams::validate(const std::string& prefix) const {
  if (!(std::abs(radius_error_fraction) < 0.1))
    return prefix + "radius_error_fraction in (-0.1, 0.1)";
  if (!(slip_stiffness > 1.0)) return prefix + "slip_stiffness must be > 1";
  if (!(display_overread_fraction >= 0.0 && display_overread_fraction < 0.2)) {
    return prefix + "display_overread_fraction in [0, 0.2)";
  }
  return "";
}

StaticLoads static_loads(const TrueVehicle& v, const MassProperties& m) {
  const double w = m.mass_kg * v.gravity_mps2;
  const double l = v.wheelbase_m;
  StaticLoads s;
  s.front_axle_n = w * (l - m.cg_x_m) / l;
  s.rear_axle_n = w * m.cg_x_m / l;
  const double right = 0.5 - m.cg_y_m / v.track_m;
  s.front_right_n = s.front_axle_n * right;
  s.front_left_n = s.front_axle_n - s.front_right_n;
  s.rear_right_n = s.rear_axle_n * right;
  s.rear_left_n = s.rear_axle_n - s.rear_right_n;
  return s;
}

AxleCorneringStiffness static_cornering_stiffness(const TrueVehicle& v, const MassProperties& m) {
  const StaticLoads s = static_loads(v, m);
  AxleCorneringStiffness c;
  c.front_n_per_rad = wheel_cornering_stiffness(v.front_tyre, s.front_left_n) +
                      wheel_cornering_stiffness(v.front_tyre, s.front_right_n);
  c.rear_n_per_rad = wheel_cornering_stiffness(v.rear_tyre, s.rear_left_n) +
                     wheel_cornering_stiffness(v.rear_tyre, s.rear_right_n);
  return c;
}

}  // namespace vmass::sim

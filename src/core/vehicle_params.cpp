#include "vmass/core/vehicle_params.hpp"

#include <cmath>
#include <limits>
#include <utility>

#include "vmass/core/param_check.hpp"

namespace vmass {

double VehicleParams::rotating_mass_for_gear(int gear, bool gear_valid) const {
  if (gear_valid && gear >= 1 &&
      static_cast<std::size_t>(gear) <= rotating_mass_by_gear_kg.size()) {
    return rotating_mass_by_gear_kg[static_cast<std::size_t>(gear) - 1];
  }
  return rotating_mass_kg;
}

double VehicleParams::overall_ratio(int gear) const {
  if (!knows_driveline() || gear < 1 || static_cast<std::size_t>(gear) > gear_ratios.size()) {
    return 0.0;
  }
  return gear_ratios[static_cast<std::size_t>(gear) - 1] * final_drive_ratio;
}

double VehicleParams::wheel_torque_from_engine_nm(double engine_torque_nm, int gear) const {
  const double ratio = overall_ratio(gear);
  if (!(ratio > 0.0)) return std::numeric_limits<double>::quiet_NaN();
  // Losses take from the torque flowing to the wheels, and add to the drag of a dragged engine.
  const double efficiency =
      engine_torque_nm >= 0.0 ? driveline_efficiency : 1.0 / driveline_efficiency;
  return engine_torque_nm * ratio * efficiency;
}

std::string VehicleParams::validate() const {
  ParamCheck c("vehicle");
  c.positive("empty_mass_kg", empty_mass_kg);
  c.positive("wheelbase_m", wheelbase_m);
  c.in_open_range("cg_to_front_axle_m", cg_to_front_axle_m, 0.0, wheelbase_m);
  c.positive("wheel_radius_m", wheel_radius_m);
  c.non_negative("brake_gain_n_per_pa", brake_gain_n_per_pa);
  c.positive("steering_ratio", steering_ratio);
  c.positive("cornering_stiffness_front_n_per_rad", cornering_stiffness_front_n_per_rad);
  c.positive("cornering_stiffness_rear_n_per_rad", cornering_stiffness_rear_n_per_rad);
  c.non_negative("rotating_mass_kg", rotating_mass_kg);
  for (std::size_t i = 0; i < rotating_mass_by_gear_kg.size(); ++i) {
    c.non_negative("rotating_mass_by_gear_kg[" + std::to_string(i) + "]",
                   rotating_mass_by_gear_kg[i]);
  }
  c.positive("gravity_mps2", gravity_mps2);
  if (!(max_mass_kg > empty_mass_kg)) c.fail("max_mass_kg", "must be above empty_mass_kg");
  c.non_negative("drag_area_m2", drag_area_m2);
  c.positive("air_density_kg_per_m3", air_density_kg_per_m3);
  for (const auto& [key, value] :
       {std::pair{"rolling_resistance_coeff", rolling_resistance_coeff},
        std::pair{"wheel_torque_accuracy_fraction", wheel_torque_accuracy_fraction},
        std::pair{"wheel_radius_accuracy_fraction", wheel_radius_accuracy_fraction}}) {
    if (!(value >= 0.0 && value < 0.5)) c.fail(key, "must be in [0, 0.5)");
  }
  if (!(std::abs(pitch_gradient_deg_per_g) < 10.0)) {
    c.fail("pitch_gradient_deg_per_g", "must be in (-10, 10)");
  }
  c.non_negative("pitch_gradient_std_deg_per_g", pitch_gradient_std_deg_per_g);
  if (!(rotating_mass_accuracy_fraction >= 0.0 && rotating_mass_accuracy_fraction <= 1.0)) {
    c.fail("rotating_mass_accuracy_fraction", "must be in [0, 1]");
  }
  for (std::size_t i = 0; i < gear_ratios.size(); ++i) {
    c.positive("gear_ratios[" + std::to_string(i) + "]", gear_ratios[i]);
  }
  c.non_negative("final_drive_ratio", final_drive_ratio);
  if (!(driveline_efficiency > 0.5 && driveline_efficiency <= 1.0)) {
    c.fail("driveline_efficiency", "must be in (0.5, 1]");
  }
  c.positive("max_driveline_slip_fraction", max_driveline_slip_fraction);
  c.non_negative("engine_inertia_kgm2", engine_inertia_kgm2);
  if (!(driveline_efficiency_accuracy_fraction >= 0.0 &&
        driveline_efficiency_accuracy_fraction < 0.5)) {
    c.fail("driveline_efficiency_accuracy_fraction", "must be in [0, 0.5)");
  }
  if (torque_converter_stall_torque_ratio != 0.0) {
    if (!(torque_converter_stall_torque_ratio > 1.0 && torque_converter_stall_torque_ratio < 5.0)) {
      c.fail("torque_converter_stall_torque_ratio", "must be 0 (unknown) or in (1, 5)");
    }
    if (!(torque_converter_coupling_speed_ratio > 0.5 &&
          torque_converter_coupling_speed_ratio < 1.0)) {
      c.fail("torque_converter_coupling_speed_ratio",
             "must be in (0.5, 1) with torque_converter_stall_torque_ratio");
    }
  }
  if (!(torque_converter_map_accuracy_fraction >= 0.0 &&
        torque_converter_map_accuracy_fraction <= 1.0)) {
    c.fail("torque_converter_map_accuracy_fraction", "must be in [0, 1]");
  }
  if (!(torque_converter_turbine_inertia_share >= 0.0 &&
        torque_converter_turbine_inertia_share <= 1.0)) {
    c.fail("torque_converter_turbine_inertia_share", "must be in [0, 1]");
  }
  return c.message();
}

double SuspensionParams::wheel_force_n(double deflection_m) const {
  const double linear = stiffness_n_per_m * (deflection_m - empty_deflection_m);
  if (!is_progressive() || !(deflection_m > progressive_knee_m)) return linear;
  const double beyond = deflection_m - progressive_knee_m;
  const double empty_beyond = std::max(0.0, empty_deflection_m - progressive_knee_m);
  return linear + progressive_rate_n_per_m2 * (beyond * beyond - empty_beyond * empty_beyond);
}

std::string SuspensionParams::validate() const {
  ParamCheck c("suspension");
  if (!carries_load()) return c.message();
  c.positive("stiffness_n_per_m", stiffness_n_per_m);
  c.finite("empty_deflection_m", empty_deflection_m);
  c.non_negative("progressive_rate_n_per_m2", progressive_rate_n_per_m2);
  if (is_progressive()) c.finite("progressive_knee_m", progressive_knee_m);
  c.positive_or_inf("linear_range_kg", linear_range_kg);
  c.positive_or_inf("calibrated_range_kg", calibrated_range_kg);
  return c.message();
}

}  // namespace vmass

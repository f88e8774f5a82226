#include "vmass/baselines/nominal_vehicle.hpp"

#include <cmath>

namespace vmass::baselines {
namespace {

bool finite_at_least(double value, double bound) { return std::isfinite(value) && value >= bound; }

}  // namespace

std::string NominalVehicle::validate() const {
  if (!(std::isfinite(empty_mass_kg) && empty_mass_kg > 0.0)) return "empty_mass_kg must be > 0";
  if (!(std::isfinite(wheel_radius_m) && wheel_radius_m > 0.0)) return "wheel_radius_m must be > 0";
  if (!finite_at_least(brake_gain_n_per_pa, 0.0)) return "brake_gain_n_per_pa must be >= 0";
  if (!finite_at_least(rotating_mass_kg, 0.0)) return "rotating_mass_kg must be >= 0";
  if (!finite_at_least(drag_area_m2, 0.0)) return "drag_area_m2 must be >= 0";
  if (!finite_at_least(air_density_kg_per_m3, 0.0)) return "air_density_kg_per_m3 must be >= 0";
  if (!finite_at_least(rolling_resistance_coeff, 0.0)) {
    return "rolling_resistance_coeff must be >= 0";
  }
  if (!(std::isfinite(gravity_mps2) && gravity_mps2 > 0.0)) return "gravity_mps2 must be > 0";
  return "";
}

}  // namespace vmass::baselines

#include "vmass/calibrate/load_geometry.hpp"

#include "vmass/core/param_check.hpp"

namespace vmass::calibrate {

LoadGeometry LoadGeometry::from_vehicle(const VehicleParams& vehicle) {
  LoadGeometry g;
  g.wheelbase_m = vehicle.wheelbase_m;
  g.cg_to_front_axle_m = vehicle.cg_to_front_axle_m;
  g.gravity_mps2 = vehicle.gravity_mps2;
  return g;
}

double LoadGeometry::wheel_force_per_kg() const {
  return gravity_mps2 * cg_to_front_axle_m / (2.0 * wheelbase_m);
}

std::string LoadGeometry::validate() const {
  ParamCheck c("vehicle");
  c.positive("wheelbase_m", wheelbase_m);
  c.in_open_range("cg_to_front_axle_m", cg_to_front_axle_m, 0.0, wheelbase_m);
  c.positive("gravity_mps2", gravity_mps2);
  return c.message();
}

}  // namespace vmass::calibrate

#include "vmass/sim/tyre.hpp"

#include <cmath>

namespace vmass::sim {

std::string TyreParams::validate(const std::string& prefix) const {
  if (!(cornering_stiffness_per_load_per_rad > 0.0)) {
    return prefix + "cornering_stiffness_per_load_per_rad must be > 0";
  }
  if (!(reference_load_n > 0.0)) return prefix + "reference_load_n must be > 0";
  if (!(load_exponent > 0.0 && load_exponent <= 1.0)) {
    return prefix + "load_exponent must be in (0, 1]";
  }
  if (!(friction_coeff > 0.0)) return prefix + "friction_coeff must be > 0";
  if (!(shape_factor > 1.0 && shape_factor < 2.0)) return prefix + "shape_factor must be in (1, 2)";
  if (!(curvature_factor <= 1.0)) return prefix + "curvature_factor must be <= 1";
  if (!(relaxation_length_m > 0.0)) return prefix + "relaxation_length_m must be > 0";
  return "";
}

double wheel_cornering_stiffness(const TyreParams& p, double fz_n) {
  if (!(fz_n > 0.0)) return 0.0;
  return p.cornering_stiffness_per_load_per_rad * p.reference_load_n *
         std::pow(fz_n / p.reference_load_n, p.load_exponent);
}

double wheel_lateral_force(const TyreParams& p, double slip_rad, double fz_n) {
  if (!(fz_n > 0.0)) return 0.0;
  const double d = p.friction_coeff * fz_n;
  const double c = p.shape_factor;
  const double b = wheel_cornering_stiffness(p, fz_n) / (c * d);
  const double ba = b * slip_rad;
  const double e = p.curvature_factor;
  return -d * std::sin(c * std::atan(ba - e * (ba - std::atan(ba))));
}

}  // namespace vmass::sim

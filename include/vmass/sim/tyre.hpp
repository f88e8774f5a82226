// Tyre: the simulated car's lateral tyre force, a Pacejka magic formula per wheel whose
// cornering stiffness depends on the wheel load.
//
//   C_alpha(F_z) = k_c F_ref (F_z / F_ref)^n                       small-slip cornering stiffness
//   F_y(alpha, F_z) = -D sin(C atan(B alpha - E (B alpha - atan(B alpha))))
//   D = mu F_z,  B = C_alpha(F_z) / (C D)                           so dF_y/dalpha(0) = -C_alpha
//
// alpha is the ISO 8855 slip angle, alpha = atan(v_y,wheel / v_x,wheel) - delta, so a positive
// slip angle gives a force to the right (negative F_y). The estimator's lateral block uses the
// paper's linear tyre F_y = C_alpha alpha with its own sign convention (see
// vmass/core/lateral_forces.hpp: its alpha is minus this one). THE ESTIMATOR'S ASSUMPTION is
// that C_alpha per axle is the small-slip slope of this curve at the static axle load of the
// scenario; the simulator writes exactly that value into config.yaml. It differs from the truth
// (a) at larger slip (saturation: about 5 % less force at a_y = 3.5 m/s^2), (b) when the load moves
// between wheels (lateral and longitudinal load transfer, n < 1 makes an axle lose stiffness), and
// (c) after the load changes (load_step).
//
// Pure functions; thread-safe.
#pragma once

#include <string>

namespace vmass::sim {

struct TyreParams {
  double cornering_stiffness_per_load_per_rad = 18.0;  ///< k_c: C_alpha / F_z at F_ref, 1/rad
  double reference_load_n = 4000.0;                    ///< F_ref
  double load_exponent = 0.8;                          ///< n: C_alpha grows less than linearly
  double friction_coeff = 1.0;                         ///< mu (dry asphalt)
  double shape_factor = 1.3;                           ///< C of the magic formula
  double curvature_factor = -0.3;                      ///< E of the magic formula (<= 1)
  double relaxation_length_m = 0.35;                   ///< sigma of the slip-angle lag

  std::string validate(const std::string& prefix) const;
};

/// Small-slip cornering stiffness of one wheel at load fz_n, N/rad (0 for fz_n <= 0).
double wheel_cornering_stiffness(const TyreParams& p, double fz_n);

/// Lateral force of one wheel, N, ISO sign (opposes the slip angle). 0 for fz_n <= 0.
double wheel_lateral_force(const TyreParams& p, double slip_rad, double fz_n);

}  // namespace vmass::sim

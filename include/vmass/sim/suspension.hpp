// Suspension: the rear-right corner of the simulated car, the one the deflection sensor of the
// paper's eq. (3) sits on. A linear spring with a progressive bump stop beyond a knee, a linear
// damper, and a corner mass driven by the wheel's vertical load (static share plus dynamic load
// transfer, computed by VehicleModel):
//
//   F_s(z) = c z + k2 max(0, z - z_knee)^2                   z: compression from free length
//   m_c z'' = (F_z,rr - m_u g) - F_s(z) - d z'                 m_c = static sprung corner mass
//
// At standstill z settles to F_s^-1(F_z,rr - m_u g). The sensor reads z - z_ref (+ its noise and
// zero offset, see SensorSpec); in the sensor's coordinates the curve is the one config.yaml
// describes: F - F_empty = c (z_s - z0) + k2 max(0, z_s - z_knee,s)^2 with z0 the empty reading.
//
// Pure functions; thread-safe.
#pragma once

#include <string>

namespace vmass::sim {

struct SuspensionParams {
  double stiffness_n_per_m = 30000.0;        ///< c: linear wheel rate (paper: 30 kN/m)
  double knee_compression_m = 0.126;         ///< z_knee: bump stop engages (about 30 mm above
                                             ///< the empty car's static compression)
  double progressive_rate_n_per_m2 = 2.0e6;  ///< k2
  double damping_n_s_per_m = 1800.0;         ///< d: about 30 % of critical
  double unsprung_mass_kg = 40.0;            ///< m_u: wheel, brake, hub, half the links
  double sensor_reference_m = 0.085;         ///< z_ref: compression at which the sensor reads 0

  std::string validate(const std::string& prefix) const;
};

/// Spring force F_s(z), N (the spring does not pull: 0 for z <= 0).
double spring_force(const SuspensionParams& p, double compression_m);

/// Inverse of spring_force for force_n >= 0 (closed form: the quadratic above the knee).
double spring_compression(const SuspensionParams& p, double force_n);

}  // namespace vmass::sim

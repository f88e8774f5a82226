#include "vmass/sim/suspension.hpp"

#include <algorithm>
#include <cmath>

namespace vmass::sim {

std::string SuspensionParams::validate(const std::string& prefix) const {
  if (!(stiffness_n_per_m > 0.0)) return prefix + "stiffness_n_per_m must be > 0";
  if (!(knee_compression_m > 0.0)) return prefix + "knee_compression_m must be > 0";
  if (!(progressive_rate_n_per_m2 >= 0.0)) return prefix + "progressive_rate_n_per_m2 must be >= 0";
  if (!(damping_n_s_per_m > 0.0)) return prefix + "damping_n_s_per_m must be > 0";
  if (!(unsprung_mass_kg >= 0.0)) return prefix + "unsprung_mass_kg must be >= 0";
  if (!std::isfinite(sensor_reference_m)) return prefix + "sensor_reference_m must be finite";
  return "";
}

double spring_force(const SuspensionParams& p, double compression_m) {
  if (!(compression_m > 0.0)) return 0.0;
  const double beyond = std::max(0.0, compression_m - p.knee_compression_m);
  return p.stiffness_n_per_m * compression_m + p.progressive_rate_n_per_m2 * beyond * beyond;
}

double spring_compression(const SuspensionParams& p, double force_n) {
  if (!(force_n > 0.0)) return 0.0;
  const double c = p.stiffness_n_per_m;
  const double knee_force = c * p.knee_compression_m;
  if (force_n <= knee_force || p.progressive_rate_n_per_m2 <= 0.0) return force_n / c;
  // k2 u^2 + c u - (F - c z_knee) = 0 with u = z - z_knee >= 0.
  const double k2 = p.progressive_rate_n_per_m2;
  const double rhs = force_n - knee_force;
  const double u = 2.0 * rhs / (c + std::sqrt(c * c + 4.0 * k2 * rhs));
  return p.knee_compression_m + u;
}

}  // namespace vmass::sim

#include "vmass/sim/scenario.hpp"

#include <algorithm>
#include <cmath>

namespace vmass::sim {

MassProperties Scenario::mass_at(double t_s) const {
  // Same formulas as add_payload, accumulated without allocating (called at 1 kHz).
  const MassProperties& e = vehicle.empty;
  double m = e.mass_kg;
  double mx = m * e.cg_x_m;
  double my = m * e.cg_y_m;
  double mz = m * e.cg_z_m;
  double mxx = 0.0;  // sum m_i x_i^2 (+ y^2) about the origin, items only
  auto add = [&](const LoadItem& it, double scale) {
    const double mi = it.mass_kg * scale;
    if (mi == 0.0) return;
    m += mi;
    mx += mi * it.x_m;
    my += mi * it.y_m;
    mz += mi * it.z_m;
    mxx += mi * (it.x_m * it.x_m + it.y_m * it.y_m);
  };
  for (const LoadItem& it : initial_payload) add(it, 1.0);
  for (const LoadChange& c : load_changes) {
    double f = 0.0;
    if (t_s >= c.start_s + c.duration_s) {
      f = 1.0;
    } else if (t_s > c.start_s) {
      f = (t_s - c.start_s) / c.duration_s;
    }
    for (const LoadItem& it : c.items) add(it, f);
  }
  MassProperties out;
  out.mass_kg = m;
  out.cg_x_m = mx / m;
  out.cg_y_m = my / m;
  out.cg_z_m = mz / m;
  // Parallel axis: I = I_e + M_e |p_e - p_cg|^2 + sum m_i |p_i - p_cg|^2, expanded.
  const double dx = e.cg_x_m - out.cg_x_m;
  const double dy = e.cg_y_m - out.cg_y_m;
  const double items_m = m - e.mass_kg;
  const double items_mx = mx - e.mass_kg * e.cg_x_m;
  const double items_my = my - e.mass_kg * e.cg_y_m;
  const double items_about_cg = mxx - 2.0 * (out.cg_x_m * items_mx + out.cg_y_m * items_my) +
                                items_m * (out.cg_x_m * out.cg_x_m + out.cg_y_m * out.cg_y_m);
  out.yaw_inertia_kgm2 = e.yaw_inertia_kgm2 + e.mass_kg * (dx * dx + dy * dy) + items_about_cg;
  return out;
}

std::string Scenario::validate() const {
  if (name.empty()) return "name must not be empty";
  if (!(duration_s > 0.0 && duration_s <= 7200.0)) return "duration_s must be in (0, 7200]";
  if (!(tick_rate_hz > 0.0 && tick_rate_hz <= 1000.0)) return "tick_rate_hz must be in (0, 1000]";
  const double ratio = integration_rate_hz / tick_rate_hz;
  if (!(ratio >= 1.0) || std::abs(ratio - std::round(ratio)) > 1e-9) {
    return "integration_rate_hz must be an integer multiple of tick_rate_hz";
  }
  if (!(integration_rate_hz <= 10000.0)) return "integration_rate_hz must be <= 10000";
  if (!(integration_rate_hz >= 500.0)) return "integration_rate_hz must be >= 500 (stiff tyres)";
  if (!(initial_speed_mps >= 0.0 && initial_speed_mps <= 60.0)) {
    return "initial_speed_mps must be in [0, 60]";
  }
  if (auto m = vehicle.validate(); !m.empty()) return m;
  for (const LoadChange& c : load_changes) {
    if (!(c.duration_s > 0.0) || !std::isfinite(c.start_s)) {
      return "load_changes: duration_s must be > 0 and start_s finite";
    }
  }
  for (double t : {0.0, duration_s}) {
    const MassProperties m = mass_at(t);
    if (!(m.mass_kg > 0.5 * vehicle.empty.mass_kg)) return "payload: mass drops below half empty";
    if (!(m.cg_x_m > 0.0 && m.cg_x_m < vehicle.wheelbase_m)) {
      return "payload: centre of gravity leaves the wheelbase";
    }
  }
  if (auto m = road.validate(); !m.empty()) return m;
  if (auto m = wind.validate(); !m.empty()) return m;
  if (auto m = driver.validate(); !m.empty()) return m;
  if (auto m = driver_params.validate(); !m.empty()) return m;
  if (auto m = sensors.validate(); !m.empty()) return m;
  return "";
}

}  // namespace vmass::sim

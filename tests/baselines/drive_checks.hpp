// Running a baseline over a drive and reading how it converged.
#pragma once

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "longitudinal_drive.hpp"
#include "vmass/baselines/baseline_factory.hpp"

namespace vmass::baselines::testing {

struct DriveResult {
  BaselineEstimate final_estimate;
  double final_error = 0.0;          ///< relative: mass / truth - 1
  double worst_error_late = 0.0;     ///< largest |relative error| over the last quarter
  bool mass_throughout_late = true;  ///< has_mass at every tick of the last quarter
};

inline DriveResult run_baseline(const std::string& name, const NominalVehicle& vehicle,
                                const std::vector<vmass::Sample>& samples, double truth_kg,
                                double tick_rate_hz = 100.0) {
  const auto baseline = make_baseline(name, vehicle, tick_rate_hz);
  DriveResult r;
  const std::size_t late = 3 * samples.size() / 4;
  for (std::size_t k = 0; k < samples.size(); ++k) {
    baseline->step(samples[k]);
    if (k < late) continue;
    const BaselineEstimate e = baseline->estimate();
    r.mass_throughout_late = r.mass_throughout_late && e.has_mass;
    r.worst_error_late = std::max(r.worst_error_late, std::abs(e.mass_kg / truth_kg - 1.0));
  }
  r.final_estimate = baseline->estimate();
  r.final_error = r.final_estimate.mass_kg / truth_kg - 1.0;
  return r;
}

/// Production-like sensor noise for a passenger car (per 100 Hz tick).
inline DriveSensors car_sensor_noise() {
  DriveSensors n;
  n.accel_x_std_mps2 = 0.02;
  n.accel_y_std_mps2 = 0.02;
  n.speed_std_mps = 0.02;
  n.torque_std_nm = 20.0;
  n.brake_std_pa = 3000.0;
  return n;
}

}  // namespace vmass::baselines::testing

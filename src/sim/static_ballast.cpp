#include "vmass/sim/static_ballast.hpp"

#include <cmath>
#include <cstdio>

#include "vmass/config/suspension_section.hpp"

namespace vmass::sim {
namespace {

std::string num(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.10g", v);
  return buf;
}

}  // namespace

std::pair<double, double> BallastSchedule::written_window(int k) const {
  const double end = first_hold_s + k * (ramp_s + hold_s);
  const double start = k == 0 ? 0.0 : end - hold_s;
  return {start + settle_s, end};
}

std::string BallastSchedule::validate() const {
  if (steps < 1) return "ballast.steps must be >= 1";
  if (!(step_kg > 0.0)) return "ballast.step_kg must be > 0";
  if (!(ramp_s > 0.0)) return "ballast.ramp_s must be > 0";
  if (!(settle_s >= 0.0) || !(hold_s > settle_s) || !(first_hold_s > settle_s)) {
    return "ballast.hold_s and first_hold_s must exceed settle_s >= 0";
  }
  return "";
}

Scenario static_ballast_scenario(const BallastSchedule& schedule) {
  Scenario s;
  s.name = "static_ballast";
  s.description =
      "static test of the paper's Fig. 9: empty car at standstill, 8 ballast steps of 100 kg at "
      "the centre of gravity held 20 s each, bump stop beyond ~414 kg; also writes ballast.csv";
  s.duration_s = schedule.duration_s();
  s.initial_speed_mps = 0.0;
  s.driver.speed_mps = PiecewiseLinear(0.0);
  const MassProperties& e = s.vehicle.empty;
  for (int k = 1; k <= schedule.steps; ++k) {
    LoadChange step;
    step.start_s = schedule.first_hold_s + (k - 1) * (schedule.ramp_s + schedule.hold_s);
    step.duration_s = schedule.ramp_s;
    step.items = {{schedule.step_kg, e.cg_x_m, e.cg_y_m, e.cg_z_m}};
    s.load_changes.push_back(step);
  }
  return s;
}

BallastTruth ballast_truth(const SimulationResult& result, const BallastSchedule& schedule) {
  BallastTruth t;
  const TrueVehicle& v = result.vehicle;
  const SuspensionParams& sp = v.rear_right_suspension;
  const ChannelSpec& sensor = result.sensors.rear_right_deflection_m;
  const StaticLoads empty = static_loads(v, v.empty);
  const double z_empty =
      spring_compression(sp, empty.rear_right_n - sp.unsprung_mass_kg * v.gravity_mps2);
  t.stiffness_n_per_m = sp.stiffness_n_per_m;
  t.sensor_offset_m = sensor.bias;
  t.sensor_noise_std_m = sensor.noise_std;
  t.sensor_resolution_m = sensor.resolution;
  t.empty_deflection_m = z_empty - sp.sensor_reference_m + sensor.bias;
  t.progressive_knee_m = sp.knee_compression_m - sp.sensor_reference_m + sensor.bias;
  t.progressive_rate_n_per_m2 = sp.progressive_rate_n_per_m2;
  t.knee_added_mass_kg = 2.0 * v.wheelbase_m * sp.stiffness_n_per_m *
                         (sp.knee_compression_m - z_empty) / (v.empty.cg_x_m * v.gravity_mps2);
  for (int k = 0; k <= schedule.steps; ++k) {
    const auto [from_s, to_s] = schedule.written_window(k);
    double sum = 0.0;
    long n = 0;
    for (const TruthRow& row : result.truth) {
      const double time_s = static_cast<double>(row.time_us) * 1e-6;
      if (time_s >= from_s && time_s < to_s) {
        sum += row.rear_right_deflection_m;
        ++n;
      }
    }
    t.added_mass_kg.push_back(schedule.added_mass_kg(k));
    t.mean_deflection_m.push_back(n > 0 ? sum / static_cast<double>(n) + sensor.bias : NAN);
  }
  return t;
}

std::string ballast_csv(const SimulationResult& result, const BallastSchedule& schedule) {
  std::string csv = "added_mass_kg,rear_right_deflection_mm\n";
  for (int k = 0; k <= schedule.steps; ++k) {
    const auto [from_s, to_s] = schedule.written_window(k);
    const std::string mass = num(schedule.added_mass_kg(k));
    for (const Sample& s : result.samples) {
      const double time_s = static_cast<double>(s.time_us) * 1e-6;
      if (time_s < from_s || time_s >= to_s || !s.has(Input::kRearRightDeflection) ||
          !std::isfinite(s.rear_right_deflection_m)) {
        continue;
      }
      char buf[64];
      std::snprintf(buf, sizeof buf, "%.5f", s.rear_right_deflection_m * 1e3);
      csv += mass + "," + buf + "\n";
    }
  }
  return csv;
}

std::string suspension_truth_yaml(const SimulationResult& result, const BallastSchedule& schedule) {
  const BallastTruth t = ballast_truth(result, schedule);
  std::string y;
  y += "# True rear-right suspension of the simulated car (static_ballast), in the deflection\n";
  y += "# sensor's coordinates: what a perfect calibration finds (the sensor's zero offset is\n";
  y += "# part of empty_deflection_m and progressive_knee_m). Curve, as the config loader reads\n";
  y += "# it: F - F_empty = c (z - z0) + k2 max(0, z - z_knee)^2.\n";
  vmass::SuspensionParams suspension;  // the estimator's (config) parameters
  suspension.stiffness_n_per_m = t.stiffness_n_per_m;
  suspension.empty_deflection_m = t.empty_deflection_m;
  suspension.progressive_knee_m = t.progressive_knee_m;
  suspension.progressive_rate_n_per_m2 = t.progressive_rate_n_per_m2;
  suspension.linear_range_kg = t.knee_added_mass_kg;
  suspension.calibrated_range_kg = schedule.added_mass_kg(schedule.steps);
  y += suspension_section_yaml(suspension, {{"linear_range_kg", "ballast that reaches the knee"}});
  y += "sensor:\n";
  y += "  zero_offset_m: " + num(t.sensor_offset_m) + "\n";
  y += "  noise_std_m: " + num(t.sensor_noise_std_m) + "\n";
  y += "  resolution_m: " + num(t.sensor_resolution_m) + "\n";
  y += "vehicle:\n";
  y += "  empty_mass_kg: " + num(result.vehicle.empty.mass_kg) + "\n";
  y += "  wheelbase_m: " + num(result.vehicle.wheelbase_m) + "\n";
  y += "  cg_to_front_axle_m: " + num(result.vehicle.empty.cg_x_m) + "\n";
  y += "  gravity_mps2: " + num(result.vehicle.gravity_mps2) + "\n";
  y += "steps:  # noise-free mean reading over each ballast.csv window\n";
  for (std::size_t k = 0; k < t.added_mass_kg.size(); ++k) {
    y += "  - {added_mass_kg: " + num(t.added_mass_kg[k]) +
         ", deflection_m: " + num(t.mean_deflection_m[k]) + "}\n";
  }
  return y;
}

}  // namespace vmass::sim

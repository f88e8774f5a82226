#include "vmass/sim/csv_writer.hpp"

#include <charconv>
#include <cmath>
#include <sstream>

#include "text_file.hpp"

namespace vmass::sim {

namespace {

struct TruthColumn {
  const char* name;
  double (*get)(const TruthRow&);
};

// Order: the columns docs/formats.md fixes first, then the rest.
const TruthColumn kTruthColumns[] = {
    {"mass_kg", [](const TruthRow& r) { return r.mass_kg; }},
    {"speed_mps", [](const TruthRow& r) { return r.speed_mps; }},
    {"grade_rad", [](const TruthRow& r) { return r.grade_rad; }},
    {"lateral_velocity_mps", [](const TruthRow& r) { return r.lateral_velocity_mps; }},
    {"yaw_rate_radps", [](const TruthRow& r) { return r.yaw_rate_radps; }},
    {"accel_x_mps2", [](const TruthRow& r) { return r.accel_x_mps2; }},
    {"accel_y_mps2", [](const TruthRow& r) { return r.accel_y_mps2; }},
    {"wheel_torque_nm", [](const TruthRow& r) { return r.wheel_torque_nm; }},
    {"brake_pressure_pa", [](const TruthRow& r) { return r.brake_pressure_pa; }},
    {"brake_force_n", [](const TruthRow& r) { return r.brake_force_n; }},
    {"drag_force_n", [](const TruthRow& r) { return r.drag_force_n; }},
    {"rolling_resistance_n", [](const TruthRow& r) { return r.rolling_resistance_n; }},
    {"rotating_mass_kg", [](const TruthRow& r) { return r.rotating_mass_kg; }},
    {"gear", [](const TruthRow& r) { return static_cast<double>(r.gear); }},
    {"steering_wheel_angle_rad", [](const TruthRow& r) { return r.steering_wheel_angle_rad; }},
    {"road_wheel_angle_rad", [](const TruthRow& r) { return r.road_wheel_angle_rad; }},
    {"bank_rad", [](const TruthRow& r) { return r.bank_rad; }},
    {"long_accel_mps2", [](const TruthRow& r) { return r.long_accel_mps2; }},
    {"x_m", [](const TruthRow& r) { return r.x_m; }},
    {"y_m", [](const TruthRow& r) { return r.y_m; }},
    {"yaw_rad", [](const TruthRow& r) { return r.yaw_rad; }},
    {"distance_m", [](const TruthRow& r) { return r.distance_m; }},
    {"cg_x_m", [](const TruthRow& r) { return r.cg_x_m; }},
    {"cg_y_m", [](const TruthRow& r) { return r.cg_y_m; }},
    {"front_axle_load_n", [](const TruthRow& r) { return r.front_axle_load_n; }},
    {"rear_axle_load_n", [](const TruthRow& r) { return r.rear_axle_load_n; }},
    {"rear_right_load_n", [](const TruthRow& r) { return r.rear_right_load_n; }},
    {"rear_right_deflection_m", [](const TruthRow& r) { return r.rear_right_deflection_m; }},
    {"lateral_force_front_n", [](const TruthRow& r) { return r.lateral_force_front_n; }},
    {"lateral_force_rear_n", [](const TruthRow& r) { return r.lateral_force_rear_n; }},
    {"slip_front_rad", [](const TruthRow& r) { return r.slip_front_rad; }},
    {"slip_rear_rad", [](const TruthRow& r) { return r.slip_rear_rad; }},
    {"wheel_force_noise_n", [](const TruthRow& r) { return r.wheel_force_noise_n; }},
    {"stopped", [](const TruthRow& r) { return r.stopped ? 1.0 : 0.0; }},
    {"hub_torque_nm", [](const TruthRow& r) { return r.hub_torque_nm; }},
    {"converter_ratio", [](const TruthRow& r) { return r.converter_ratio; }},
    {"engine_speed_radps", [](const TruthRow& r) { return r.engine_speed_radps; }},
    {"accessory_on", [](const TruthRow& r) { return r.accessory_on ? 1.0 : 0.0; }},
    {"wind_head_mps", [](const TruthRow& r) { return r.wind_head_mps; }},
    {"wind_cross_mps", [](const TruthRow& r) { return r.wind_cross_mps; }},
    {"esc_brake_force_n", [](const TruthRow& r) { return r.esc_brake_force_n; }},
    {"abs_active", [](const TruthRow& r) { return r.abs_active ? 1.0 : 0.0; }},
    {"bump_force_n", [](const TruthRow& r) { return r.bump_force_n; }},
    {"viscous_loss_n", [](const TruthRow& r) { return r.viscous_loss_n; }},
    {"brake_temperature_c", [](const TruthRow& r) { return r.brake_temperature_c; }},
    {"brake_gain_scale", [](const TruthRow& r) { return r.brake_gain_scale; }},
};

void append_number(std::string& out, double v) {
  if (!std::isfinite(v)) return;
  if (v == 0.0) v = 0.0;  // no "-0"
  char buf[32];
  const auto res = std::to_chars(buf, buf + sizeof buf, v, std::chars_format::general, 12);
  out.append(buf, res.ptr);
}

void append_time(std::string& out, TimeUs t_us) {
  append_number(out, static_cast<double>(t_us) / 1e6);
}

}  // namespace

std::string format_number(double v) {
  std::string s;
  append_number(s, v);
  return s;
}

std::string truth_csv_header() {
  std::string h = "time_s";
  for (const TruthColumn& c : kTruthColumns) {
    h += ',';
    h += c.name;
  }
  return h;
}

void write_samples_csv(std::ostream& os, const std::vector<Sample>& samples) {
  std::string line;
  os << kSamplesCsvHeader << '\n';
  for (const Sample& s : samples) {
    line.clear();
    append_time(line, s.time_us);
    for (int i = 0; i < kInputCount; ++i) {
      const auto in = static_cast<Input>(i);
      line += ',';
      if (s.has(in)) append_number(line, s.value(in));
    }
    line += '\n';
    os << line;
  }
}

void write_truth_csv(std::ostream& os, const std::vector<TruthRow>& truth) {
  std::string line;
  os << truth_csv_header() << '\n';
  for (const TruthRow& r : truth) {
    line.clear();
    append_time(line, r.time_us);
    for (const TruthColumn& c : kTruthColumns) {
      line += ',';
      append_number(line, c.get(r));
    }
    line += '\n';
    os << line;
  }
}

std::string write_csv_files(const SimulationResult& result, const std::string& dir) {
  std::ostringstream samples;
  write_samples_csv(samples, result.samples);
  if (auto m = detail::write_text_file(dir + "/samples.csv", samples.str()); !m.empty()) return m;
  std::ostringstream truth;
  write_truth_csv(truth, result.truth);
  return detail::write_text_file(dir + "/truth.csv", truth.str());
}

}  // namespace vmass::sim

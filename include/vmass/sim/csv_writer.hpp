// CSV output of a simulation: samples.csv (the estimator's inputs) and truth.csv (the hidden
// states), exactly as docs/formats.md specifies. Numbers are written locale-free with
// std::to_chars (12 significant digits, '.' decimal point); time_s is exact to the microsecond.
// An invalid Sample input, or a non-finite value, is written as an empty cell.
//
// Stateless functions; thread-safe on distinct streams.
#pragma once

#include <ostream>
#include <string>
#include <string_view>
#include <vector>

#include "vmass/core/sample.hpp"
#include "vmass/sim/simulator.hpp"

namespace vmass::sim {

/// Header of samples.csv (docs/formats.md).
inline constexpr std::string_view kSamplesCsvHeader =
    "time_s,wheel_torque_nm,brake_pressure_pa,accel_x_mps2,accel_y_mps2,yaw_rate_radps,"
    "speed_mps,steering_wheel_angle_rad,rear_right_deflection_m,gear,brake_switch,engine_torque_nm,"
    "engine_speed_radps";

/// Header of truth.csv: time_s,mass_kg,speed_mps,grade_rad,lateral_velocity_mps,
/// yaw_rate_radps,accel_x_mps2,accel_y_mps2, then the other TruthRow fields.
std::string truth_csv_header();

/// A number as written in our CSV files ("" when not finite).
std::string format_number(double v);

void write_samples_csv(std::ostream& os, const std::vector<Sample>& samples);
void write_truth_csv(std::ostream& os, const std::vector<TruthRow>& truth);

/// Writes DIR/samples.csv and DIR/truth.csv (DIR must exist). "" or a message naming the file.
std::string write_csv_files(const SimulationResult& result, const std::string& dir);

}  // namespace vmass::sim

#include "vmass/csv/samples_csv.hpp"

#include <cmath>
#include <locale>
#include <sstream>

#include "vmass/csv/csv.hpp"
#include "vmass/io/excerpt.hpp"
#include "vmass/io/regular_file.hpp"

namespace vmass {

std::string samples_csv_column(Input in) {
  switch (in) {
    case Input::kWheelTorque:
      return "wheel_torque_nm";
    case Input::kBrakePressure:
      return "brake_pressure_pa";
    case Input::kAccelX:
      return "accel_x_mps2";
    case Input::kAccelY:
      return "accel_y_mps2";
    case Input::kYawRate:
      return "yaw_rate_radps";
    case Input::kSpeed:
      return "speed_mps";
    case Input::kSteeringWheelAngle:
      return "steering_wheel_angle_rad";
    case Input::kRearRightDeflection:
      return "rear_right_deflection_m";
    case Input::kGear:
      return "gear";
    case Input::kBrakeSwitch:
      return "brake_switch";
    case Input::kEngineTorque:
      return "engine_torque_nm";
    case Input::kEngineSpeed:
      return "engine_speed_radps";
    case Input::kCount:
      break;
  }
  return "";
}

SamplesCsvReader::SamplesCsvReader(const std::string& path)
    : path_(path), lines_(in_, kMaxLineBytes), column_of_input_(kInputCount, -1) {
  // A regular file or a pipe; a directory or a device (/dev/zero) is refused before reading.
  if (const std::string why = io::check_input_file(path, true); !why.empty()) {
    error_ = path + ": cannot open the samples file: " + why;
    return;
  }
  in_.open(path, std::ios::binary);
  if (!in_) {
    error_ = path + ": cannot open the samples file";
    return;
  }
  std::string header;
  if (!lines_.next(&header) || lines_.overlong()) {
    error_ = path + ":1: " +
             (!lines_.error().empty() ? "read error: " + lines_.error()
              : lines_.overlong()     ? std::string("header longer than 64 KiB")
                                      : std::string("empty file, expected a header"));
    return;
  }
  line_ = 1;
  const std::vector<std::string> names = split_csv_line(header);
  column_count_ = names.size();
  for (std::size_t c = 0; c < names.size(); ++c) {
    if (names[c] == "time_s") time_column_ = static_cast<int>(c);
    for (int i = 0; i < kInputCount; ++i) {
      if (names[c] == samples_csv_column(static_cast<Input>(i))) {
        column_of_input_[static_cast<std::size_t>(i)] = static_cast<int>(c);
      }
    }
  }
  if (time_column_ < 0) error_ = path + ":1: the header has no time_s column";
}

void SamplesCsvReader::warn(const std::string& message) {
  ++skipped_rows_;
  if (warnings_.size() < 100) {
    warnings_.push_back(path_ + ":" + std::to_string(line_) + ": " + message);
  }
}

std::optional<Sample> SamplesCsvReader::next() {
  if (!error_.empty()) return std::nullopt;
  std::string row;
  while (lines_.next(&row)) {
    ++line_;
    if (lines_.overlong()) {
      warn("row longer than 64 KiB");
      continue;
    }
    if (row.empty() || row.front() == '#') continue;
    const std::vector<std::string> cells = split_csv_line(row);
    if (cells.size() != column_count_) {
      warn("expected " + std::to_string(column_count_) + " cells, got " +
           std::to_string(cells.size()));
      continue;
    }
    Sample s;
    double time_s = 0.0;
    if (!parse_csv_number(cells[static_cast<std::size_t>(time_column_)], &time_s) ||
        !std::isfinite(time_s)) {
      warn("time_s is not a number: '" +
           io::excerpt(cells[static_cast<std::size_t>(time_column_)]) + "'");
      continue;
    }
    if (!(std::abs(time_s) <= kMaxAbsTimeS)) {
      warn("time_s out of range (|time_s| <= 1e10 s)");
      continue;
    }
    s.time_us = from_seconds(time_s);
    // Compared with the previous row, not the previous good one: one row stamped far away
    // costs that row (and the one after), never the rest of the file.
    const bool increases = !has_last_time_ || s.time_us > last_time_us_;
    has_last_time_ = true;
    last_time_us_ = s.time_us;
    if (!increases) {
      warn("time_s does not increase");
      continue;
    }
    bool bad = false;
    for (int i = 0; i < kInputCount && !bad; ++i) {
      const int c = column_of_input_[static_cast<std::size_t>(i)];
      if (c < 0) continue;
      const std::string& cell = cells[static_cast<std::size_t>(c)];
      if (cell.empty()) continue;  // invalid at this tick
      double v = 0.0;
      if (!parse_csv_number(cell, &v)) {
        warn(samples_csv_column(static_cast<Input>(i)) + " is not a number: '" + io::excerpt(cell) +
             "'");
        bad = true;
        break;
      }
      // NaN or infinite values are data faults: the input is invalid at this tick.
      if (std::isfinite(v)) s.set(static_cast<Input>(i), v);
    }
    if (bad) continue;
    return s;
  }
  if (!lines_.error().empty()) read_error_ = path_ + ": read error: " + lines_.error();
  return std::nullopt;
}

}  // namespace vmass

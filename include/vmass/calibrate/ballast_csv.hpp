// Ballast CSV reader: the two CSV shapes vmass-calibrate accepts.
//
//   steps:  added_mass_<unit>, rear_right_deflection_<unit>     one row per sample or per step,
//           any number of samples per step, any row order, other columns ignored;
//   series: time_<unit>, rear_right_deflection_<unit> [, speed_mps]   a recording of the whole
//           test (a vmass samples.csv is one), for the plateau detector.
// Units are read from the column name and converted to SI:
//   added_mass: kg, t, lb        rear_right_deflection: m, cm, mm, um, in        time: s, ms, us
// A column with an unknown or missing unit is an error naming the column; a cell that is not a
// number, or NaN / inf, is an error naming file:line and column. In a series an empty cell marks
// an invalid input at that row (the samples.csv convention) and the row is skipped. Numbers are
// parsed locale-free; '#' lines and blank lines are skipped; CRLF and a leading UTF-8 byte order
// mark are accepted. Every row has the header's field count (one more is most often a decimal
// comma). Values beyond a physical bound (added mass outside [-1000, 100000] kg, |deflection| >
// 1 m: a unit error) are errors naming file:line, the column, the value and the bound; so are
// --masses values beyond the mass bound (parse_mass_list).
//
// Pure functions (read_ballast_csv reads the file); thread-safe.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "vmass/calibrate/ballast_step.hpp"
#include "vmass/calibrate/plateau_detector.hpp"

namespace vmass::calibrate {

enum class BallastCsvKind { kSteps, kSeries };

struct BallastCsv {
  BallastCsvKind kind = BallastCsvKind::kSteps;
  std::vector<BallastSample> samples;   ///< kSteps
  std::vector<DeflectionPoint> series;  ///< kSeries
  long skipped_rows = 0;                ///< kSeries rows with an empty deflection or time cell
};

struct BallastCsvRead {
  std::optional<BallastCsv> csv;
  std::string error;  ///< "file:line: column: message" when csv is empty
  bool ok() const { return csv.has_value(); }
};

BallastCsvRead read_ballast_csv(const std::string& path);
BallastCsvRead parse_ballast_csv(std::string_view text, const std::string& name);

/// Parses a comma-separated list of masses in kg ("0,100,200" or "0:100:800" for a range with
/// a step). "" and *out filled, or a message.
std::string parse_mass_list(const std::string& text, std::vector<double>* out);

}  // namespace vmass::calibrate

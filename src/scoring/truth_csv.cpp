#include "vmass/scoring/truth_csv.hpp"

#include <cmath>
#include <sstream>

#include "vmass/csv/csv.hpp"
#include "vmass/io/line_reader.hpp"
#include "vmass/io/regular_file.hpp"

namespace vmass::scoring {

std::optional<Truth> load_truth_csv(const std::string& path, std::string* error) {
  const io::FileText file = io::read_regular_file(path, io::kMaxTableBytes, "truth file");
  if (!file.ok()) {
    *error = file.error;
    return std::nullopt;
  }
  std::istringstream in(file.text);
  io::LineReader lines(in);
  std::string line;
  lines.next(&line);
  const auto header = split_csv_line(line);
  if (header.size() < 2 || header[0] != "time_s" || header[1] != "mass_kg") {
    *error = path + ":1: expected a header starting with time_s,mass_kg";
    return std::nullopt;
  }
  std::vector<TimeUs> times;
  std::vector<double> masses;
  while (lines.next(&line)) {
    if (line.empty()) continue;
    const auto cells = split_csv_line(line);
    double t = 0.0, m = 0.0;
    const std::string at = path + ":" + std::to_string(lines.line_number()) + ": ";
    if (cells.size() < 2 || !parse_csv_number(cells[0], &t) || !parse_csv_number(cells[1], &m) ||
        !(std::abs(t) <= 1e10) || !std::isfinite(m)) {
      *error = at + "expected time_s,mass_kg numbers (|time_s| <= 1e10 s)";
      return std::nullopt;
    }
    if (!times.empty() && from_seconds(t) < times.back()) {
      *error = at + "time_s goes back";
      return std::nullopt;
    }
    times.push_back(from_seconds(t));
    masses.push_back(m);
  }
  if (times.empty()) {
    *error = path + ": no rows";
    return std::nullopt;
  }
  return Truth(std::move(times), std::move(masses));
}

}  // namespace vmass::scoring
